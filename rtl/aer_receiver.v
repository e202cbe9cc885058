// Address-event receiver for one tile's bus: the RTL that aesim verifies against its SystemC
// reference model (models/receiver/receiver_cycle_model).
//
//  - A three-flop synchronizer on the asynchronous Req (aer_req_sync); decisions read only its
//    second and third flops, never the first, which may be metastable. The address (bundled data)
//    and the contention line are latched once Req has been seen high on two consecutive edges by
//    those settled flops, so a Req glitch shorter than a clock period is ignored.
//  - addr_i and contention_i are bundled data: they are sampled without a synchronizer because
//    the bus drives them before it raises Req and holds them until Ack rises, and the latch
//    happens at least two clock periods after Req rises. The bus must meet that: the data settle
//    no later than Req, plus the flops' setup time (a single pixel's address is stable; a second
//    pixel joining ORs its bits in and raises contention in the same step, both before a latch
//    two periods away would see them only if they settle in under 2 periods minus setup).
//  - 4-phase handshake: Ack rises with the latch, falls once Req has been seen low on two
//    consecutive edges. Ack rises on the 4th edge after Req rises, falls on the 4th after it falls.
//  - Timestamp of the latch edge k (k rising edges since reset): floor(k / prescale_i) mod
//    2^TS_WIDTH, the ticks completed by that edge, the edge included (aer_timestamp's next
//    value); or ts_i when ts_external_i is set, so the clock may be stopped while the bus is idle
//    and a free-running timestamp still be used.
//  - Events go into a FIFO read as a valid/ready stream of {timestamp, address, flags}; flags[0]
//    is the contention line sampled with the address. With discard_collisions_i a flagged event
//    is counted and discarded instead.
//  - A full FIFO (fifo_limit_i words) drops the event and counts an overflow, or, with
//    HOLD_WHEN_FULL, withholds Ack until there is room, stretching the bus transaction.
//  - Counters: events written to the FIFO, transactions latched with contention, overflows.
//  - idle_o: nothing can change until Req rises (the clock may be stopped).
module aer_receiver #(
    parameter ADDR_WIDTH = 16,
    parameter TS_WIDTH = 32,
    parameter DEPTH = 64,
    parameter HOLD_WHEN_FULL = 0,
    parameter COUNT_WIDTH = 32,
    parameter PRESCALE_WIDTH = 16,
    parameter CW = $clog2(DEPTH + 1)
) (
    input  wire                      clk_i,
    input  wire                      rst_ni,
    // Bus
    input  wire                      req_i,
    input  wire [    ADDR_WIDTH-1:0] addr_i,
    input  wire                      contention_i,
    output wire                      ack_o,
    // Configuration, static while running
    input  wire [PRESCALE_WIDTH-1:0] prescale_i,
    input  wire [            CW-1:0] fifo_limit_i,
    input  wire                      discard_collisions_i,
    input  wire                      ts_external_i,
    input  wire [      TS_WIDTH-1:0] ts_i,
    // Event stream
    output wire                      evt_valid_o,
    input  wire                      evt_ready_i,
    output wire [      TS_WIDTH-1:0] evt_ts_o,
    output wire [    ADDR_WIDTH-1:0] evt_addr_o,
    output wire                      evt_flags_o,
    // Status
    output wire [   COUNT_WIDTH-1:0] events_o,
    output wire [   COUNT_WIDTH-1:0] collisions_o,
    output wire [   COUNT_WIDTH-1:0] overflows_o,
    output wire [            CW-1:0] fifo_count_o,
    output wire                      idle_o
);
  localparam S_IDLE = 1'b0;
  localparam S_ACK = 1'b1;
  localparam WORD = TS_WIDTH + ADDR_WIDTH + 1;
  localparam [COUNT_WIDTH-1:0] ONE = {{(COUNT_WIDTH - 1) {1'b0}}, 1'b1};

  wire req_s2, req_s3, req_any;
  aer_req_sync u_sync (
      .clk_i (clk_i),
      .rst_ni(rst_ni),
      .d_i   (req_i),
      .q2_o  (req_s2),
      .q3_o  (req_s3),
      .any_o (req_any)
  );

  wire [TS_WIDTH-1:0] ts_counter;
  aer_timestamp #(
      .TS_WIDTH(TS_WIDTH),
      .PRESCALE_WIDTH(PRESCALE_WIDTH)
  ) u_timestamp (
      .clk_i(clk_i),
      .rst_ni(rst_ni),
      .prescale_i(prescale_i),
      .ts_next_o(ts_counter)
  );
  wire [TS_WIDTH-1:0] ts_now = ts_external_i ? ts_i : ts_counter;

  reg state_q, state_d;
  reg ack_q, ack_d;
  reg push;
  reg [COUNT_WIDTH-1:0] events_q, events_d, collisions_q, collisions_d, overflows_q, overflows_d;
  wire fifo_full, fifo_valid;
  wire [WORD-1:0] fifo_out;

  wire req_high = req_s2 && req_s3;
  wire req_low = !req_s2 && !req_s3;

  always @(*) begin
    state_d = state_q;
    ack_d = ack_q;
    push = 1'b0;
    events_d = events_q;
    collisions_d = collisions_q;
    overflows_d = overflows_q;
    case (state_q)
      S_IDLE: begin
        if (req_high) begin
          if (contention_i && discard_collisions_i) begin
            collisions_d = collisions_q + ONE;
            ack_d = 1'b1;
            state_d = S_ACK;
          end else if (fifo_full) begin
            if (HOLD_WHEN_FULL == 0) begin
              overflows_d = overflows_q + ONE;
              if (contention_i) collisions_d = collisions_q + ONE;
              ack_d = 1'b1;
              state_d = S_ACK;
            end
          end else begin
            push = 1'b1;
            events_d = events_q + ONE;
            if (contention_i) collisions_d = collisions_q + ONE;
            ack_d = 1'b1;
            state_d = S_ACK;
          end
        end
      end
      default: begin
        if (req_low) begin
          ack_d = 1'b0;
          state_d = S_IDLE;
        end
      end
    endcase
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= S_IDLE;
      ack_q <= 1'b0;
      events_q <= {COUNT_WIDTH{1'b0}};
      collisions_q <= {COUNT_WIDTH{1'b0}};
      overflows_q <= {COUNT_WIDTH{1'b0}};
    end else begin
      state_q <= state_d;
      ack_q <= ack_d;
      events_q <= events_d;
      collisions_q <= collisions_d;
      overflows_q <= overflows_d;
    end
  end

  aer_fifo #(
      .WIDTH(WORD),
      .DEPTH(DEPTH),
      .CW(CW)
  ) u_fifo (
      .clk_i(clk_i),
      .rst_ni(rst_ni),
      .limit_i(fifo_limit_i),
      .push_i(push),
      .data_i({ts_now, addr_i, contention_i}),
      .full_o(fifo_full),
      .valid_o(fifo_valid),
      .data_o(fifo_out),
      .ready_i(evt_ready_i),
      .count_o(fifo_count_o)
  );

  assign ack_o = ack_q;
  assign evt_valid_o = fifo_valid;
  assign evt_ts_o = fifo_out[WORD-1:ADDR_WIDTH+1];
  assign evt_addr_o = fifo_out[ADDR_WIDTH:1];
  assign evt_flags_o = fifo_out[0];
  assign events_o = events_q;
  assign collisions_o = collisions_q;
  assign overflows_o = overflows_q;
  assign idle_o = (state_q == S_IDLE) && !req_any && !fifo_valid;
endmodule
