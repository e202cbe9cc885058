// Two-flop synchronizer for an asynchronous input (the bus Req).
module aer_sync2 (
    input  wire clk_i,
    input  wire rst_ni,
    input  wire d_i,
    output wire q1_o,  // first stage, exposed so the receiver can require two agreeing samples
    output wire q2_o
);
  reg s1_q, s2_q;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_q <= 1'b0;
      s2_q <= 1'b0;
    end else begin
      s1_q <= d_i;
      s2_q <= s1_q;
    end
  end

  assign q1_o = s1_q;
  assign q2_o = s2_q;
endmodule
