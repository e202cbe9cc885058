// A receiver written as an FPGA team might: an active-low asynchronous reset, two flops on Req,
// a registered Ack that follows them, the address captured on the synchronised Req's rise into a
// 4-word FIFO that drops when full (Ack still given) and counts the drops in 8 bits, wrapping or,
// with SATURATE, held at 255; contention discards; the stamp, a free-running count of edges,
// taken at capture and packed with the address into one output word.
module arx #(
    parameter int DEPTH_LOG = 2,
    parameter bit SATURATE  = 1'b0
) (
    input  logic        clk_i,
    input  logic        rst_ni,
    input  logic        aer_req_i,
    output logic        aer_ack_o,
    input  logic [ 9:0] aer_addr_i,
    input  logic        aer_coll_i,
    output logic        m_valid_o,
    input  logic        m_ready_i,
    output logic [31:0] m_data_o,   // {stamp, 6'b0, address}
    output logic [ 7:0] dropped_o
);
  logic s1, s2, s2_q;
  logic [15:0] now;
  logic [31:0] mem[1 << DEPTH_LOG];
  // One bit wider than an index: equal indices with the top bits apart is full.
  logic [DEPTH_LOG:0] wr, rd;
  wire full = wr[DEPTH_LOG] != rd[DEPTH_LOG] && wr[DEPTH_LOG-1:0] == rd[DEPTH_LOG-1:0];
  wire empty = wr == rd;
  wire capture = s2 && !s2_q && !aer_coll_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1 <= 1'b0;
      s2 <= 1'b0;
      s2_q <= 1'b0;
      aer_ack_o <= 1'b0;
      now <= '0;
      wr <= '0;
      dropped_o <= '0;
    end else begin
      s1 <= aer_req_i;
      s2 <= s1;
      s2_q <= s2;
      now <= now + 16'd1;
      aer_ack_o <= s2;
      if (capture && !full) wr <= wr + 1'b1;
      if (capture && full && !(SATURATE && dropped_o == 8'hFF)) dropped_o <= dropped_o + 8'd1;
    end
  end
  // The FIFO's words have no reset (a word is read only after it is written; capture is low in reset).
  always_ff @(posedge clk_i) begin
    if (capture && !full) mem[wr[DEPTH_LOG-1:0]] <= {now, 6'b0, aer_addr_i};
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) rd <= '0;
    else if (m_valid_o && m_ready_i) rd <= rd + 1'b1;
  end
  assign m_valid_o = !empty;
  assign m_data_o  = mem[rd[DEPTH_LOG-1:0]];
endmodule
