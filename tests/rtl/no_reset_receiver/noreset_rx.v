// A receiver without a reset, as FPGA designs are often written: every register starts from its
// initial value (Verilator and Icarus both honour them; an FPGA's configuration loads them). Two
// flops on Req, one output word with valid/ready, and Ack held until that word has room.
module noreset_rx (
    input  wire       clk,
    input  wire       req,
    input  wire [9:0] addr,
    output reg        ack = 1'b0,
    output reg        valid = 1'b0,
    input  wire       ready,
    output reg  [9:0] out_addr = 10'd0
);
  reg r1 = 1'b0, r2 = 1'b0;
  always @(posedge clk) begin
    r1 <= req;
    r2 <= r1;
    if (valid && ready) valid <= 1'b0;
    if (r2 && !ack && (!valid || ready)) begin
      out_addr <= addr;
      valid <= 1'b1;
      ack <= 1'b1;
    end else if (!r2 && ack) begin
      ack <= 1'b0;
    end
  end
endmodule
