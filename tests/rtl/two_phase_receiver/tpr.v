// A two-phase (transition-signalling) receiver: every change of Req, either way, is an event,
// answered by one change of Ack. Req passes two flops; the event is taken when the synchronised
// Req differs from the last one taken and the one-word output register is free (or being taken),
// and Ack changes at that edge, with the address and the stamp (ticks of PRESCALE cycles since
// reset) captured into the output: back-pressure holds Ack ("hold"). No contention input. An
// asynchronous active-low reset puts Req's flops and Ack at IDLE, the level both lines rest at
// (IDLE = 1: a link whose lines idle high, described with `active = "low"`). Described for
// `aesim verify` with `[bus] handshake = "two_phase"` (tpr.toml).
`default_nettype none
module tpr #(
    parameter integer AW = 10,
    parameter integer TW = 16,
    parameter integer PRESCALE = 8,
    parameter [0:0] IDLE = 1'b0
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          req,
    input  wire [AW-1:0] addr,
    output reg           ack,
    output reg           out_valid,
    input  wire          out_ready,
    output reg  [AW-1:0] out_addr,
    output reg  [TW-1:0] out_ts
);
  reg          req_meta, req_sync;
  localparam integer DW = PRESCALE > 1 ? $clog2(PRESCALE) : 1;
  reg [DW-1:0] div;
  reg [TW-1:0] ticks;
  wire         waiting = req_sync != ack;
  wire         take = waiting && (!out_valid || out_ready);

  always @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      req_meta <= IDLE;
      req_sync <= IDLE;
      ack      <= IDLE;
    end else begin
      req_meta <= req;
      req_sync <= req_meta;
      if (take) ack <= req_sync;
    end
  end

  always @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      out_valid <= 1'b0;
      out_addr  <= {AW{1'b0}};
      out_ts    <= {TW{1'b0}};
    end else if (take) begin
      out_valid <= 1'b1;
      out_addr  <= addr;
      out_ts    <= ticks;
    end else if (out_ready) begin
      out_valid <= 1'b0;
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
endmodule
`default_nettype wire
