// A receiver whose output is a data-ready flag rather than a stream: the word is latched and
// `word_ready` raised when a transaction is taken, and both Ack and the flag fall once the sender
// has dropped Req. A consumer loads the word on the flag's rise; the flag stays high for the whole
// handshake, so it is not a one-cycle valid. Synchronous active-high reset, a two-flop Req
// synchroniser, no back-pressure and no contention input (a collision's OR of addresses passes).
// Described for `aesim verify` with `valid = { port = "word_ready", beat = "rise" }` (lvr.toml).
`default_nettype none
module lvr #(
    parameter integer AW = 10
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          req,
    input  wire [AW-1:0] addr,
    output reg           ack,
    output reg  [AW-1:0] word,
    output reg           word_ready
);
  reg req_meta, req_seen;

  always @(posedge clk) begin
    if (rst) begin
      req_meta   <= 1'b0;
      req_seen   <= 1'b0;
      ack        <= 1'b0;
      word       <= {AW{1'b0}};
      word_ready <= 1'b0;
    end else begin
      req_meta <= req;
      req_seen <= req_meta;
      if (!ack && req_seen) begin
        ack        <= 1'b1;
        word       <= addr;
        word_ready <= 1'b1;
      end else if (ack && !req_seen) begin
        ack        <= 1'b0;
        word_ready <= 1'b0;
      end
    end
  end
endmodule
`default_nettype wire
