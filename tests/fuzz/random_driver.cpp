// A bounded random-input driver for LLVMFuzzerTestOneInput, for compilers without libFuzzer
// (the default g++ build): mutates the seed corpus (bit flips, cuts, splices, lengths set to
// 0, 2 GB or random) for a fixed time, with a printed seed so that a failure can be replayed.
//   traci_fuzz_random [--seconds S] [--seed N] [CORPUS_DIR...]
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::string mutate(std::string s, const std::vector<std::string>& seeds, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const int rounds = 1 + static_cast<int>(pick(6));
  for (int i = 0; i < rounds; ++i) {
    switch (pick(7)) {
      case 0:  // flip a bit
        if (!s.empty()) s[pick(s.size())] = static_cast<char>(s[pick(s.size())] ^ (1 << pick(8)));
        break;
      case 1:  // random byte
        if (!s.empty()) s[pick(s.size())] = static_cast<char>(pick(256));
        break;
      case 2:  // cut
        s.resize(pick(s.size() + 1));
        break;
      case 3: {  // splice another seed in
        const std::string& o = seeds[pick(seeds.size())];
        s.insert(pick(s.size() + 1), o.substr(pick(o.size() + 1)));
        break;
      }
      case 4: {  // a hostile 4-byte length somewhere
        static const std::uint32_t lengths[] = {0, 1, 3, 4, 5, 0x7FFFFFFF, 0x80000000u, 0xFFFFFFFF, 256, 65536};
        const std::uint32_t v = pick(2) ? lengths[pick(std::size(lengths))] : static_cast<std::uint32_t>(rng());
        const std::size_t at = pick(s.size() + 1);
        const char bytes[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                               static_cast<char>(v)};
        s.replace(at, std::min<std::size_t>(4, s.size() - at), bytes, 4);
        break;
      }
      case 5:  // duplicate a chunk
        if (!s.empty()) {
          const std::size_t at = pick(s.size());
          s.insert(at, s.substr(at, pick(32)));
        }
        break;
      default:  // random tail
        for (std::size_t n = pick(16); n > 0; --n) s.push_back(static_cast<char>(pick(256)));
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 5;
  std::uint64_t seed = std::random_device{}();
  std::vector<std::string> seeds;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seconds" && i + 1 < argc) {
      seconds = std::stod(argv[++i]);
    } else if (a == "--seed" && i + 1 < argc) {
      seed = std::stoull(argv[++i]);
    } else {
      // Seed folders may hold sub-folders (scenarios/nightly) and markers (.keep): files only.
      for (const auto& f : std::filesystem::recursive_directory_iterator(a)) {
        if (!f.is_regular_file()) continue;
        std::ifstream in(f.path(), std::ios::binary);
        seeds.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
    }
  }
  if (seeds.empty()) seeds.emplace_back("\0\0\0\x05\x02", 5);
  const std::string name = std::filesystem::path(argv[0]).filename().string();
  std::cout << name << ": seed " << seed << ", " << seeds.size() << " corpus file(s), " << seconds << " s\n";
  std::mt19937_64 rng(seed);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  long long runs = 0;
  for (const auto& s : seeds) LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  while (std::chrono::steady_clock::now() < end) {
    for (int batch = 0; batch < 256; ++batch, ++runs) {
      const std::string input = mutate(seeds[rng() % seeds.size()], seeds, rng);
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
    }
  }
  std::cout << name << ": " << runs << " inputs, no crash\n";
  return 0;
}
