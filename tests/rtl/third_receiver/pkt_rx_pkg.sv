// The third receiver's package: its states and the packet it puts out.
package pkt_rx_pkg;
  typedef enum logic [0:0] {
    IDLE,
    WAIT_RELEASE
  } state_t;
  localparam int ADDR_W = 10;
  localparam int PKT_W = 72;
endpackage
