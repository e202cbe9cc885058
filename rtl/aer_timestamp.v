// Timestamp counter: advances by one every prescale_i clock cycles and wraps modulo 2^TS_WIDTH.
// ts_next_o is the value the counter takes at the coming rising edge: sampled at the k-th rising
// edge since reset it reads floor(k / prescale_i) mod 2^TS_WIDTH, the ticks completed by that
// edge. A prescale_i of 0 is treated as 1.
module aer_timestamp #(
    parameter TS_WIDTH = 32,
    parameter PRESCALE_WIDTH = 16
) (
    input  wire                      clk_i,
    input  wire                      rst_ni,
    input  wire [PRESCALE_WIDTH-1:0] prescale_i,
    output wire [TS_WIDTH-1:0]       ts_next_o
);
  reg [PRESCALE_WIDTH-1:0] div_q, div_d;
  reg [TS_WIDTH-1:0] ts_q, ts_d;
  wire last_cycle = (prescale_i <= {{(PRESCALE_WIDTH - 1) {1'b0}}, 1'b1}) ||
                    (div_q == prescale_i - {{(PRESCALE_WIDTH - 1) {1'b0}}, 1'b1});

  always @(*) begin
    div_d = div_q + {{(PRESCALE_WIDTH - 1) {1'b0}}, 1'b1};
    ts_d  = ts_q;
    if (last_cycle) begin
      div_d = {PRESCALE_WIDTH{1'b0}};
      ts_d  = ts_q + {{(TS_WIDTH - 1) {1'b0}}, 1'b1};
    end
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      div_q <= {PRESCALE_WIDTH{1'b0}};
      ts_q  <= {TS_WIDTH{1'b0}};
    end else begin
      div_q <= div_d;
      ts_q  <= ts_d;
    end
  end

  assign ts_next_o = ts_d;
endmodule
