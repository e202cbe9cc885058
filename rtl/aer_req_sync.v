// Synchronizer for the asynchronous bus Req: three flops in a chain. The first may go metastable
// when Req changes near a clock edge, so nothing but the second flop reads it; q2_o and q3_o are
// settled and the receiver decides on them. Two settled stages let the receiver require two
// agreeing samples (a Req glitch shorter than a clock period is never seen high twice).
module aer_req_sync (
    input  wire clk_i,
    input  wire rst_ni,
    input  wire d_i,
    output wire q2_o,
    output wire q3_o,
    output wire any_o  // some stage holds a 1: a Req is still passing through
);
  reg s1_q, s2_q, s3_q;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_q <= 1'b0;
      s2_q <= 1'b0;
      s3_q <= 1'b0;
    end else begin
      s1_q <= d_i;
      s2_q <= s1_q;
      s3_q <= s2_q;
    end
  end

  assign q2_o  = s2_q;
  assign q3_o  = s3_q;
  assign any_o = s1_q || s2_q || s3_q;
endmodule
