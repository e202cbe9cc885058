// A receiver that takes the address when it sees Req fall, not when it sees Req rise: correct
// behind a sender that holds its address until Ack falls (a synchronous sender's output register,
// as clock-domain-crossing Req/Ack converters pair with), wrong behind the imager's pixels, which
// let go of the address lines with Req when Ack rises. Synchronous active-high reset; Req and the
// address pass the same two flops; a one-cycle `word_valid`, no back-pressure, no contention
// input. Described for `aesim verify` with `[bus] address_held = "until_ack_falls"` (lsr.toml).
`default_nettype none
module lsr #(
    parameter integer AW = 10
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          req,
    input  wire [AW-1:0] addr,
    output reg           ack,
    output reg  [AW-1:0] word,
    output reg           word_valid
);
  reg          req_meta, req_seen;
  reg [AW-1:0] addr_meta, addr_seen;

  always @(posedge clk) begin
    if (rst) begin
      req_meta   <= 1'b0;
      req_seen   <= 1'b0;
      addr_meta  <= {AW{1'b0}};
      addr_seen  <= {AW{1'b0}};
      ack        <= 1'b0;
      word       <= {AW{1'b0}};
      word_valid <= 1'b0;
    end else begin
      req_meta   <= req;
      req_seen   <= req_meta;
      addr_meta  <= addr;
      addr_seen  <= addr_meta;
      word_valid <= 1'b0;
      if (!ack && req_seen) begin
        ack <= 1'b1;
      end else if (ack && !req_seen) begin
        ack        <= 1'b0;
        word       <= addr_seen;
        word_valid <= 1'b1;
      end
    end
  end
endmodule
`default_nettype wire
