-- The fourth receiver of the tests (tests/rtl/fourth_receiver/arx.sv) as a VHDL team would write
-- it: upper-case names, generics, a package, signals named as Verilog's reserved words (which the
-- conversion to Verilog must escape), an active-low asynchronous reset, two flops on Req (an
-- entity of their own, req_sync.vhd), a registered Ack that follows them, the address captured on
-- the synchronised Req's rise into a FIFO of 2**DEPTH_LOG words that drops when full (Ack still
-- given) and counts the drops in 8 bits, wrapping or, with SATURATE, held at 255; contention
-- discards; the stamp, a free-running count of edges, taken at capture and packed with the address
-- into one output word.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.arx_pkg.all;

entity VARX is
  generic (
    DEPTH_LOG : positive := 2;
    SATURATE  : boolean  := false
  );
  port (
    CLK      : in  std_logic;
    RST_N    : in  std_logic;
    AER_REQ  : in  std_logic;
    AER_ACK  : out std_logic;
    AER_ADDR : in  std_logic_vector(ADDR_BITS - 1 downto 0);
    AER_COLL : in  std_logic;
    M_VALID  : out std_logic;
    M_READY  : in  std_logic;
    M_DATA   : out word_t;  -- stamp & "000000" & address
    DROPPED  : out std_logic_vector(7 downto 0)
  );
end entity;

architecture rtl of VARX is
  type mem_t is array (0 to 2 ** DEPTH_LOG - 1) of word_t;
  -- `table` and `config` are plain names in VHDL and reserved words in Verilog.
  signal table                : mem_t;
  signal config               : std_logic_vector(1 downto 0);
  signal s2, s2_q, ack_q      : std_logic;
  signal now                  : unsigned(STAMP_BITS - 1 downto 0);
  -- One bit wider than an index: equal indices with the top bits apart is full.
  signal wr, rd               : unsigned(DEPTH_LOG downto 0);
  signal drops                : unsigned(7 downto 0);
  signal full, empty, capture : std_logic;
begin
  sync : entity work.REQ_SYNC port map (CLK => CLK, RST_N => RST_N, D => AER_REQ, Q => s2);

  full    <= '1' when wr(DEPTH_LOG) /= rd(DEPTH_LOG) and wr(DEPTH_LOG - 1 downto 0) = rd(DEPTH_LOG - 1 downto 0) else '0';
  empty   <= '1' when wr = rd else '0';
  config  <= s2 & s2_q;
  capture <= '1' when config = "10" and AER_COLL = '0' else '0';

  control : process (CLK, RST_N)
  begin
    if RST_N = '0' then
      s2_q  <= '0';
      ack_q <= '0';
      now   <= (others => '0');
      wr    <= (others => '0');
      drops <= (others => '0');
    elsif rising_edge(CLK) then
      s2_q  <= s2;
      ack_q <= s2;
      now   <= now + 1;
      if capture = '1' and full = '0' then
        wr <= wr + 1;
      end if;
      if capture = '1' and full = '1' and not (SATURATE and drops = 255) then
        drops <= drops + 1;
      end if;
    end if;
  end process;

  -- The FIFO's words have no reset: a word is read only after it is written.
  store : process (CLK)
  begin
    if rising_edge(CLK) then
      if capture = '1' and full = '0' then
        table(to_integer(wr(DEPTH_LOG - 1 downto 0))) <= std_logic_vector(now) & "000000" & AER_ADDR;
      end if;
    end if;
  end process;

  take : process (CLK, RST_N)
  begin
    if RST_N = '0' then
      rd <= (others => '0');
    elsif rising_edge(CLK) then
      if empty = '0' and M_READY = '1' then
        rd <= rd + 1;
      end if;
    end if;
  end process;

  AER_ACK <= ack_q;
  M_VALID <= not empty;
  M_DATA  <= table(to_integer(rd(DEPTH_LOG - 1 downto 0)));
  DROPPED <= std_logic_vector(drops);
end architecture;
