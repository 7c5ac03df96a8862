// rk-run's content checksum (run/sha256.h) on a large file: the hashing rate of Sha256File, which rk-run
// pays for every input, tool and product it records (issue 16 item 6: OpenSSL's EVP instead of a portable
// implementation). The file (RK_BENCH_SHA256_MB MB of pseudo-random bytes, default 86) is written once to
// the temporary directory and stays in the page cache, so the figure is the hashing, not the disk.
//   BM_Sha256File   bytes/s of Sha256File
//   BM_Sha256Update bytes/s of Sha256::Update on an in-memory 1 MiB buffer
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "run/sha256.h"

namespace {

std::vector<char> RandomBytes(std::size_t n) {
  std::mt19937_64 rng(16);
  std::vector<char> b(n);
  for (std::size_t i = 0; i + 8 <= n; i += 8) {
    const std::uint64_t v = rng();
    for (int k = 0; k < 8; ++k) b[i + static_cast<std::size_t>(k)] = static_cast<char>(v >> (8 * k));
  }
  return b;
}

const std::string& BigFile() {
  static const std::string path = [] {
    const char* mb_env = std::getenv("RK_BENCH_SHA256_MB");
    const std::size_t mb = mb_env ? std::strtoul(mb_env, nullptr, 10) : 86;
    const std::string p = (std::filesystem::temp_directory_path() / "rk_bench_sha256.bin").string();
    const std::vector<char> chunk = RandomBytes(std::size_t{1} << 20);
    std::ofstream f(p, std::ios::binary);
    for (std::size_t i = 0; i < mb; ++i) f.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    return p;
  }();
  return path;
}

void BM_Sha256File(benchmark::State& state) {
  const std::string& path = BigFile();
  const auto bytes = static_cast<std::int64_t>(std::filesystem::file_size(path));
  for (auto _ : state) benchmark::DoNotOptimize(rk::run::Sha256File(path));
  state.SetBytesProcessed(state.iterations() * bytes);
}
BENCHMARK(BM_Sha256File)->Unit(benchmark::kMillisecond);

void BM_Sha256Update(benchmark::State& state) {
  const std::vector<char> buf = RandomBytes(std::size_t{1} << 20);
  for (auto _ : state) {
    rk::run::Sha256 h;
    h.Update(buf.data(), buf.size());
    benchmark::DoNotOptimize(h.HexDigest());
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(buf.size()));
}
BENCHMARK(BM_Sha256Update)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
