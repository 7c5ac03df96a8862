// CsvTable::Parse and every typed accessor (SPEC §2 CSV) on arbitrary bytes.
#include <cstdint>

#include "fuzz_util.h"
#include "io/csv.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::io::CsvTable t = rk::io::CsvTable::Parse(rk::fuzz::AsText(data, size), "fuzz.csv");
    for (std::size_t c = 0; c < t.header().size(); ++c) {
      const int col = t.RequireColumn(t.header()[c]);
      if (col != static_cast<int>(c)) std::abort();  // names are unique, so lookup finds the same column
      for (std::size_t r = 0; r < t.rows(); ++r) {
        if (t.Line(r) <= t.header_line() || t.CharColumn(r, col) == 0) std::abort();
        rk::fuzz::ExpectOnlyInputErrors([&] { (void)t.Double(r, col); });
        rk::fuzz::ExpectOnlyInputErrors([&] { (void)t.OptionalDouble(r, col); });
        rk::fuzz::ExpectOnlyInputErrors([&] { (void)t.Int(r, col); });
        (void)t.CellError(r, col, "fuzz").what();
      }
      rk::fuzz::ExpectOnlyInputErrors([&] { t.RequireNonDecreasing(col); });
      rk::fuzz::ExpectOnlyInputErrors([&] { t.RequireIncreasing(col); });
    }
    (void)t.RequireColumn("t_s");
  });
  return 0;
}
