// Synchronous FIFO of DEPTH words with a valid/ready read port. full_o rises when it holds
// limit_i words (a configuration input, 1..DEPTH), so one build serves any smaller depth.
// A push while full or a pop while empty is ignored (the receiver never does either).
module aer_fifo #(
    parameter WIDTH = 8,
    parameter DEPTH = 16,
    parameter CW = 5  // count width: holds 0..DEPTH
) (
    input  wire             clk_i,
    input  wire             rst_ni,
    input  wire [CW-1:0]    limit_i,
    input  wire             push_i,
    input  wire [WIDTH-1:0] data_i,
    output wire             full_o,
    output wire             valid_o,
    output wire [WIDTH-1:0] data_o,
    input  wire             ready_i,
    output wire [CW-1:0]    count_o
);
  localparam PW = (DEPTH > 1) ? $clog2(DEPTH) : 1;

  reg [WIDTH-1:0] mem_q[0:DEPTH-1];
  reg [PW-1:0] rd_q, rd_d, wr_q, wr_d;
  reg [CW-1:0] count_q, count_d;

  wire do_push = push_i && !full_o;
  wire do_pop = valid_o && ready_i;

  function [PW-1:0] advance(input [PW-1:0] ptr);
    advance = (ptr == DEPTH[PW-1:0] - {{(PW - 1) {1'b0}}, 1'b1}) ? {PW{1'b0}} :
                                                                  ptr + {{(PW - 1) {1'b0}}, 1'b1};
  endfunction

  always @(*) begin
    rd_d = do_pop ? advance(rd_q) : rd_q;
    wr_d = do_push ? advance(wr_q) : wr_q;
    count_d = count_q;
    if (do_push && !do_pop) count_d = count_q + {{(CW - 1) {1'b0}}, 1'b1};
    if (do_pop && !do_push) count_d = count_q - {{(CW - 1) {1'b0}}, 1'b1};
  end

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_q <= {PW{1'b0}};
      wr_q <= {PW{1'b0}};
      count_q <= {CW{1'b0}};
    end else begin
      rd_q <= rd_d;
      wr_q <= wr_d;
      count_q <= count_d;
    end
  end

  always @(posedge clk_i) begin
    if (do_push) mem_q[wr_q] <= data_i;
  end

  assign full_o = (count_q >= limit_i) || (count_q == DEPTH[CW-1:0]);
  assign valid_o = (count_q != {CW{1'b0}});
  assign data_o = mem_q[rd_q];
  assign count_o = count_q;
endmodule
