// A second address-event receiver, written for aesim's tests in another style than
// rtl/aer_receiver.v, to show that `aesim verify` needs nothing but a description: other port
// names, an active-high synchronous reset, a three-flop synchronizer followed by a glitch filter
// (so Ack comes one edge later), a power-of-two FIFO with wrap-bit pointers, collisions kept
// with a flag, 12-bit stamps of the counter as it stands before the latch edge, and a lost-event
// counter for drops.
module ae_rx_alt #(
    parameter AW = 12,
    parameter TSW = 12,
    parameter LOG_DEPTH = 3,
    parameter TICK_CYCLES = 20
) (
    input  wire           clock,
    input  wire           reset,
    input  wire           bus_req,
    input  wire [AW-1:0]  bus_addr,
    input  wire           bus_collide,
    output reg            bus_ack,
    output wire           out_valid,
    input  wire           out_ready,
    output wire [AW-1:0]  out_address,
    output wire [TSW-1:0] out_time,
    output wire [1:0]     out_flags,
    output reg  [15:0]    lost_count
);
  localparam DEPTH = 1 << LOG_DEPTH;
  localparam WORD = TSW + 1 + AW;

  // sync[0] may be metastable; sync[1] and sync[2] are settled; held is sync[2] one edge later.
  reg [2:0] sync;
  reg held;
  always @(posedge clock) begin
    if (reset) begin
      sync <= 3'b000;
      held <= 1'b0;
    end else begin
      sync <= {sync[1:0], bus_req};
      held <= sync[2];
    end
  end
  wire seen_high = sync[2] & held;
  wire seen_low = ~sync[2] & ~held;

  reg [15:0] divider;
  reg [TSW-1:0] now;
  always @(posedge clock) begin
    if (reset) begin
      divider <= 16'd0;
      now <= {TSW{1'b0}};
    end else if (divider == TICK_CYCLES - 1) begin
      divider <= 16'd0;
      now <= now + 1'b1;
    end else begin
      divider <= divider + 1'b1;
    end
  end

  reg [WORD-1:0] ring[0:DEPTH-1];
  reg [LOG_DEPTH:0] wr, rd;
  wire [LOG_DEPTH:0] used = wr - rd;
  wire full = used == DEPTH;
  assign out_valid = wr != rd;
  wire [WORD-1:0] head = ring[rd[LOG_DEPTH-1:0]];
  assign out_address = head[AW-1:0];
  assign out_flags = {1'b0, head[AW]};
  assign out_time = head[WORD-1:AW+1];

  reg busy;
  always @(posedge clock) begin
    if (reset) begin
      busy <= 1'b0;
      bus_ack <= 1'b0;
      wr <= {(LOG_DEPTH + 1) {1'b0}};
      lost_count <= 16'd0;
    end else if (!busy) begin
      if (seen_high) begin
        if (full) begin
          lost_count <= lost_count + 16'd1;
        end else begin
          ring[wr[LOG_DEPTH-1:0]] <= {now, bus_collide, bus_addr};
          wr <= wr + 1'b1;
        end
        bus_ack <= 1'b1;
        busy <= 1'b1;
      end
    end else if (seen_low) begin
      bus_ack <= 1'b0;
      busy <= 1'b0;
    end
  end

  always @(posedge clock) begin
    if (reset) rd <= {(LOG_DEPTH + 1) {1'b0}};
    else if (out_valid && out_ready) rd <= rd + 1'b1;
  end
endmodule
