// A bounded random-input driver for LLVMFuzzerTestOneInput, for compilers without libFuzzer
// (the default g++ build): mutates the seed corpus (bit flips, cuts, splices, lengths set to
// 0, 2 GB or random): a fixed number of inputs from a fixed seed by default (the same inputs on
// every run of the test command), or for a time with any seed (the soak); the seed is printed
// so that a failure can be replayed.
//   traci_fuzz_random [--runs N | --seconds S] [--seed N] [CORPUS_DIR...]
#include <algorithm>
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
  // Deterministic by default (ctest): a fixed seed and a fixed number of inputs, so the same
  // tree always tries the same inputs. The soak (scripts/soak.sh) passes --seed and --seconds.
  double seconds = 0;
  long long max_inputs = 4096;
  std::uint64_t seed = 1;
  std::vector<std::string> seeds;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seconds" && i + 1 < argc) {
      seconds = std::stod(argv[++i]);
      max_inputs = 0;
    } else if (a == "--runs" && i + 1 < argc) {
      max_inputs = std::stoll(argv[++i]);
    } else if (a == "--seed" && i + 1 < argc) {
      seed = std::stoull(argv[++i]);
    } else {
      // Seed folders may hold sub-folders (scenarios/nightly) and markers (.keep): files only,
      // in a fixed order (a directory's order is the file system's).
      std::vector<std::filesystem::path> paths;
      for (const auto& f : std::filesystem::recursive_directory_iterator(a))
        if (f.is_regular_file()) paths.push_back(f.path());
      std::sort(paths.begin(), paths.end());
      for (const auto& path : paths) {
        std::ifstream in(path, std::ios::binary);
        seeds.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
    }
  }
  if (seeds.empty()) seeds.emplace_back("\0\0\0\x05\x02", 5);
  const std::string name = std::filesystem::path(argv[0]).filename().string();
  std::cout << name << ": seed " << seed << ", " << seeds.size() << " corpus file(s), "
            << (max_inputs > 0 ? std::to_string(max_inputs) + " inputs" : std::to_string(seconds) + " s") << "\n";
  std::mt19937_64 rng(seed);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  long long runs = 0;
  for (const auto& s : seeds) LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  const auto more = [&] { return max_inputs > 0 ? runs < max_inputs : std::chrono::steady_clock::now() < end; };
  while (more()) {
    for (int batch = 0; batch < 256 && (max_inputs == 0 || runs < max_inputs); ++batch, ++runs) {
      const std::string input = mutate(seeds[rng() % seeds.size()], seeds, rng);
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
    }
  }
  std::cout << name << ": " << runs << " inputs, no crash (seed " << seed << ")\n";
  return 0;
}
