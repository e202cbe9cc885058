// A receiver whose output runs on a clock of its own: a four-phase Req/Ack input on `clk` (two
// synchroniser flops, Ack raised as the word is written) and a one-word mailbox crossing to
// `out_clk`, where the word and its stamp are offered with valid/ready. The crossing is a toggle
// each way: the input side changes `wtog` as it writes the word, the output side sees the change
// through two flops and offers the word until taken, then changes `rtog`, which the input side sees
// through two flops before it writes again (until then the mailbox is full and Ack waits: "hold").
// The word is written only while the output side offers none, so it is stable whenever offered.
// Stamps are ticks of PRESCALE input cycles since reset, taken as the word is written. One
// asynchronous active-low reset for both sides. Described for `aesim verify` with the output clock
// in `clk = ["clk", { port = "out_clk", clock = ... }]` (tcr.toml).
`default_nettype none
module tcr #(
    parameter integer AW = 10,
    parameter integer TW = 8,
    parameter integer PRESCALE = 4
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          req,
    input  wire [AW-1:0] addr,
    output reg           ack,
    input  wire          out_clk,
    output wire          out_valid,
    input  wire          out_ready,
    output wire [AW-1:0] out_addr,
    output wire [TW-1:0] out_ts
);
  localparam integer DW = PRESCALE > 1 ? $clog2(PRESCALE) : 1;

  // The input side, on clk.
  reg          req_meta, req_sync, wtog, rtog_meta, rtog_sync;
  reg [AW-1:0] word;
  reg [TW-1:0] word_ts, ticks;
  reg [DW-1:0] div;
  wire         full = wtog != rtog_sync;

  always @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      {req_meta, req_sync, rtog_meta, rtog_sync, wtog, ack} <= 6'd0;
      word    <= {AW{1'b0}};
      word_ts <= {TW{1'b0}};
    end else begin
      req_meta  <= req;
      req_sync  <= req_meta;
      rtog_meta <= rtog;
      rtog_sync <= rtog_meta;
      if (req_sync && !ack && !full) begin
        word    <= addr;
        word_ts <= ticks;
        wtog    <= !wtog;
        ack     <= 1'b1;
      end else if (!req_sync && ack) begin
        ack <= 1'b0;
      end
    end
  end

  always @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      div   <= {DW{1'b0}};
      ticks <= {TW{1'b0}};
    end else if (div == PRESCALE[DW-1:0] - 1'b1) begin
      div   <= {DW{1'b0}};
      ticks <= ticks + 1'b1;
    end else begin
      div <= div + 1'b1;
    end
  end

  // The output side, on out_clk.
  reg wtog_meta, wtog_sync, rtog;
  assign out_valid = wtog_sync != rtog;
  assign out_addr  = word;
  assign out_ts    = word_ts;

  always @(posedge out_clk or negedge rst_n) begin
    if (!rst_n) begin
      {wtog_meta, wtog_sync, rtog} <= 3'd0;
    end else begin
      wtog_meta <= wtog;
      wtog_sync <= wtog_meta;
      if (out_valid && out_ready) rtog <= !rtog;
    end
  end
endmodule
`default_nettype wire
