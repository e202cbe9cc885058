-- Two flops on Req, cleared by the active-low asynchronous reset: an entity of its own, so that
-- GHDL writes the receiver as two modules.
library ieee;
use ieee.std_logic_1164.all;

entity REQ_SYNC is
  port (
    CLK   : in  std_logic;
    RST_N : in  std_logic;
    D     : in  std_logic;
    Q     : out std_logic
  );
end entity;

architecture rtl of REQ_SYNC is
  signal first, second : std_logic;
begin
  process (CLK, RST_N)
  begin
    if RST_N = '0' then
      first  <= '0';
      second <= '0';
    elsif rising_edge(CLK) then
      first  <= D;
      second <= first;
    end if;
  end process;
  Q <= second;
end architecture;
