-- Constants and the output word's type of varx.vhd, in a package of their own: the sources are
-- analysed in the order the description lists them.
library ieee;
use ieee.std_logic_1164.all;

package arx_pkg is
  constant ADDR_BITS  : natural := 10;
  constant STAMP_BITS : natural := 16;
  subtype word_t is std_logic_vector(31 downto 0);
end package;
