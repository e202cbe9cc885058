// A Verilog top around the VHDL receiver (varx.vhd), as a mixed-language team's would be:
// lower-case ports and an active-high reset, inverted for the receiver's active-low one. The
// VHDL keeps its generics' defaults (a 4-word FIFO, a wrapping drop counter).
module mixed_top (
    input  wire        clk,
    input  wire        rst,
    input  wire        req,
    output wire        ack,
    input  wire [ 9:0] addr,
    input  wire        coll,
    output wire        valid,
    input  wire        ready,
    output wire [31:0] data,
    output wire [ 7:0] dropped
);
  VARX rx (
      .CLK(clk),
      .RST_N(!rst),
      .AER_REQ(req),
      .AER_ACK(ack),
      .AER_ADDR(addr),
      .AER_COLL(coll),
      .M_VALID(valid),
      .M_READY(ready),
      .M_DATA(data),
      .DROPPED(dropped)
  );
endmodule
