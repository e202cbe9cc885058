// A third address-event receiver, written for aesim's tests in the styles real receivers use and
// the first two do not: SystemVerilog with a package and an enum; active-low Req and Ack; a
// synchroniser whose first flop has no reset (nothing but the next flop reads it, the usual CDC
// practice), so a Req held through reset is seen at once after it; a fall-through output whose
// valid follows the synchronised Req combinationally, so the beat is taken on the edge Ack rises;
// no storage, so Ack waits for the consumer; and a 72-bit packet (a SpiNNaker-style key and
// payload) whose fields carry the address and the stamp.
// Names from the package are qualified (pkt_rx_pkg::...), not imported: yosys, which the formal
// check reads the RTL with, has no import. The state's enum is the module's own: Icarus Verilog 11
// crashes on a package's enum type.
module pkt_rx #(
    parameter int TICK_CYCLES = 10,
    parameter int TSW = 16
) (
    input  logic              clk,
    input  logic              rst_n,
    input  logic              aer_req_n,
    input  logic [pkt_rx_pkg::ADDR_W-1:0] aer_addr,
    input  logic              aer_col,
    output logic              aer_ack_n,
    output logic              pkt_valid,
    input  logic              pkt_ready,
    output logic [pkt_rx_pkg::PKT_W-1:0] pkt_data
);
  logic req_meta, req_sync;
  always_ff @(posedge clk) req_meta <= ~aer_req_n;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) req_sync <= 1'b0;
    else req_sync <= req_meta;
  end

  logic [15:0] divider;
  logic [TSW-1:0] now;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      divider <= '0;
      now <= '0;
    end else if (divider == 16'(TICK_CYCLES - 1)) begin
      divider <= '0;
      now <= now + 1'b1;
    end else begin
      divider <= divider + 1'b1;
    end
  end

  // The bus's address and contention and the counter, taken at the edge the synchroniser first
  // shows Req (the bundled data has settled by then) and held while the beat waits.
  typedef enum logic [0:0] {
    IDLE,
    WAIT_RELEASE
  } state_t;
  state_t state;
  wire offer = state == IDLE && req_sync;
  logic [TSW-1:0] stamp;
  logic [pkt_rx_pkg::ADDR_W-1:0] addr_q;
  logic col_q;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      stamp <= '0;
      addr_q <= '0;
      col_q <= 1'b0;
    end else if (!offer) begin
      stamp <= now;
      addr_q <= aer_addr;
      col_q <= aer_col;
    end
  end
  assign pkt_valid = offer && !col_q;  // a collision is acknowledged and discarded
  assign pkt_data = {32'd0, stamp, 6'd0, addr_q, 8'h00};
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state <= IDLE;
      aer_ack_n <= 1'b1;
    end else begin
      case (state)
        IDLE:
        if (offer && (col_q || pkt_ready)) begin
          state <= WAIT_RELEASE;
          aer_ack_n <= 1'b0;
        end
        WAIT_RELEASE:
        if (!req_sync) begin
          state <= IDLE;
          aer_ack_n <= 1'b1;
        end
        default: state <= IDLE;
      endcase
    end
  end
endmodule
