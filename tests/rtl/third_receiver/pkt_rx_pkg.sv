// The third receiver's package: the sizes of the bus address and of the packet it puts out.
package pkt_rx_pkg;
  localparam int ADDR_W = 10;
  localparam int PKT_W = 72;
endpackage
