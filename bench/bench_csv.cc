// CSV reading speed (issue 27 item 16, docs/benchmarks.md "Issue 27 — long logs"): io::CsvTable on a
// turret log t_s,az_deg,el_deg in the page cache. The file is RK_BENCH_CSV when set (bench/long_logs.sh
// passes its generated 300 MB log), else a 1 kHz log of RK_BENCH_CSV_ROWS rows (default 1 000 000,
// ≈ 38 MB) written once to the temporary directory.
//   BM_CsvRead          bytes/s of CsvTable::Read (the one pass: header, row offsets, lines)
//   BM_CsvReadNumbers   bytes/s of Read + Double of every cell, row by row (what a reader does)
//   BM_CountLines       bytes/s of counting '\n' with memchr over the file read in 1 MiB blocks: the
//                       in-process floor, what `wc -l` does
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/csv.h"

namespace {

const std::string& LogFile() {
  static const std::string path = [] {
    if (const char* p = std::getenv("RK_BENCH_CSV")) return std::string(p);
    const char* rows_env = std::getenv("RK_BENCH_CSV_ROWS");
    const long rows = rows_env ? std::strtol(rows_env, nullptr, 10) : 1000000;
    const std::string p = (std::filesystem::temp_directory_path() / "rk_bench_csv_turret.csv").string();
    std::ofstream f(p, std::ios::binary);
    f << "t_s,az_deg,el_deg\n";
    char line[96];
    for (long i = 0; i < rows; ++i) {
      const double x = static_cast<double>(i);
      const int n = std::snprintf(line, sizeof line, "%.6f,%.8f,%.8f\n", 1000 + x * 0.001,
                                  180 + 170 * std::sin(x * 1e-5), 20 + 15 * std::sin(x * 3e-6 + 1));
      f.write(line, n);
    }
    return p;
  }();
  return path;
}

std::int64_t FileBytes() { return static_cast<std::int64_t>(std::filesystem::file_size(LogFile())); }

void BM_CsvRead(benchmark::State& state) {
  for (auto _ : state) {
    const rk::io::CsvTable t = rk::io::CsvTable::Read(LogFile());
    benchmark::DoNotOptimize(t.rows());
  }
  state.SetBytesProcessed(state.iterations() * FileBytes());
}
BENCHMARK(BM_CsvRead)->Unit(benchmark::kMillisecond);

void BM_CsvReadNumbers(benchmark::State& state) {
  for (auto _ : state) {
    const rk::io::CsvTable t = rk::io::CsvTable::Read(LogFile());
    const int ncols = static_cast<int>(t.header().size());
    double sum = 0.0;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      for (int c = 0; c < ncols; ++c) sum += t.Double(r, c);
    }
    benchmark::DoNotOptimize(sum);
    state.counters["held_bytes_per_row"] =
        static_cast<double>(t.HeldBytes()) / static_cast<double>(std::max<std::size_t>(t.rows(), 1));
  }
  state.SetBytesProcessed(state.iterations() * FileBytes());
}
BENCHMARK(BM_CsvReadNumbers)->Unit(benchmark::kMillisecond);

void BM_CountLines(benchmark::State& state) {
  std::vector<char> buf(std::size_t{1} << 20);
  for (auto _ : state) {
    std::FILE* f = std::fopen(LogFile().c_str(), "rb");
    std::size_t lines = 0, n = 0;
    while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) {
      for (const char* p = buf.data(); (p = static_cast<const char*>(std::memchr(p, '\n', n - static_cast<std::size_t>(p - buf.data())))) != nullptr; ++p) {
        ++lines;
      }
    }
    std::fclose(f);
    benchmark::DoNotOptimize(lines);
  }
  state.SetBytesProcessed(state.iterations() * FileBytes());
}
BENCHMARK(BM_CountLines)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
