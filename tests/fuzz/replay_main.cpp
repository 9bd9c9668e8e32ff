// Runs a fuzz target without libFuzzer, in the default test run's build (gcc, the
// sanitizers): every file named on the command line (a directory: every regular file in
// it, in name order) is handed to the target's LLVMFuzzerTestOneInput once, and then, with
// --mutate N, N inputs made from them by seeded random edits (bit flips, bytes set to
// values that matter to a JSON or binary reader, inserted, erased, repeated, and one
// input's tail spliced onto another's). A broken property aborts (fuzz_check.hpp) and the
// sanitizers report memory errors and UB, as under libFuzzer; the input that did it is
// written to crash-<pid>.bin in the working directory first. This is the smoke run of
// every test run: short, the same inputs every time for a given --seed, and blind (no
// coverage guidance); the coverage-guided runs are .ci/fuzz.sh's (tests/fuzz/README.md).
//   fts_fuzz_<name>_replay [--mutate N] [--seed S] [--max-len BYTES] FILE|DIR...
// Exit codes: 0 every input held; 1 nothing to read, a file unreadable or a bad flag.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#if defined(__SANITIZE_ADDRESS__) && __has_include(<sanitizer/common_interface_defs.h>)
#include <sanitizer/common_interface_defs.h>
#define FTS_SANITIZER_DEATH_CALLBACK 1
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

using Bytes = std::vector<std::uint8_t>;

// The input being run, for the abort handler: written out before the process dies.
const Bytes* g_current = nullptr;

// Only async-signal-safe calls: it runs from a signal handler or a sanitizer's death.
void write_current() {
  if (g_current == nullptr) return;
  char name[64];
  std::snprintf(name, sizeof name, "crash-%ld.bin", static_cast<long>(::getpid()));
  const int fd = ::open(name, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    const ssize_t wrote = ::write(fd, g_current->data(), g_current->size());
    (void)wrote;
    ::close(fd);
  }
  static const char msg[] = "fuzz replay: the input is saved as crash-<pid>.bin in the working directory\n";
  const ssize_t said = ::write(2, msg, sizeof msg - 1);
  (void)said;
}

void on_signal(int sig) {
  write_current();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void run(const Bytes& input) {
  // A copy of its own size, so that a read past the input is a heap overflow (ASan).
  const Bytes data(input);
  g_current = &data;
  LLVMFuzzerTestOneInput(data.empty() ? nullptr : data.data(), data.size());
  g_current = nullptr;
}

// Values that mean something to the readers: JSON's punctuation and digits, the ends of
// the integer ranges, and a few bytes the binary encodings treat specially.
constexpr std::array<std::uint8_t, 20> kInteresting = {0x00, 0x01, 0x7f, 0x80, 0xff, '"', '{', '}', '[', ']',
                                                       ':',  ',',  '-',  '0',  '9',  'e', '\\', 0xc0, 0xcc, 0xdc};

Bytes mutate(const Bytes& in, const std::vector<Bytes>& corpus, std::mt19937_64& rng, std::size_t max_len) {
  Bytes out = in;
  const auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  const std::size_t edits = 1 + pick(4);
  for (std::size_t e = 0; e < edits; ++e) {
    switch (pick(6)) {
      case 0:  // flip a bit
        if (!out.empty()) out[pick(out.size())] ^= static_cast<std::uint8_t>(1u << pick(8));
        break;
      case 1:  // a byte set to a random or an interesting value
        if (!out.empty())
          out[pick(out.size())] = pick(2) ? static_cast<std::uint8_t>(rng()) : kInteresting[pick(kInteresting.size())];
        break;
      case 2:  // a byte inserted
        out.insert(out.begin() + static_cast<std::ptrdiff_t>(pick(out.size() + 1)),
                   pick(2) ? static_cast<std::uint8_t>(rng()) : kInteresting[pick(kInteresting.size())]);
        break;
      case 3:  // a range erased
        if (!out.empty()) {
          const std::size_t at = pick(out.size());
          const std::size_t n = std::min(out.size() - at, 1 + pick(16));
          out.erase(out.begin() + static_cast<std::ptrdiff_t>(at), out.begin() + static_cast<std::ptrdiff_t>(at + n));
        }
        break;
      case 4:  // a range repeated somewhere else
        if (!out.empty()) {
          const std::size_t at = pick(out.size());
          const std::size_t n = std::min(out.size() - at, 1 + pick(64));
          const Bytes chunk(out.begin() + static_cast<std::ptrdiff_t>(at),
                            out.begin() + static_cast<std::ptrdiff_t>(at + n));
          out.insert(out.begin() + static_cast<std::ptrdiff_t>(pick(out.size() + 1)), chunk.begin(), chunk.end());
        }
        break;
      default: {  // another input's tail spliced on at a random point
        const Bytes& other = corpus[pick(corpus.size())];
        const std::size_t cut = pick(out.size() + 1), from = pick(other.size() + 1);
        out.resize(cut);
        out.insert(out.end(), other.begin() + static_cast<std::ptrdiff_t>(from), other.end());
        break;
      }
    }
  }
  if (out.size() > max_len) out.resize(max_len);
  return out;
}

bool read_file(const std::filesystem::path& file, Bytes& out) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

bool number(const char* text, unsigned long long& out) {
  char* end = nullptr;
  out = std::strtoull(text, &end, 10);
  return end != text && *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  unsigned long long mutations = 0, seed = 1, max_len = 4096;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    unsigned long long* flag = arg == "--mutate" ? &mutations : arg == "--seed" ? &seed : arg == "--max-len" ? &max_len : nullptr;
    if (flag != nullptr) {
      if (i + 1 >= argc || !number(argv[i + 1], *flag)) {
        std::fprintf(stderr, "fuzz replay: %s needs a number\n", arg.c_str());
        return 1;
      }
      ++i;
      continue;
    }
    if (std::filesystem::is_directory(arg)) {
      std::vector<std::filesystem::path> in_dir;
      for (const auto& entry : std::filesystem::directory_iterator(arg))
        if (entry.is_regular_file()) in_dir.push_back(entry.path());
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else {
      files.emplace_back(arg);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s [--mutate N] [--seed S] [--max-len BYTES] FILE|DIR...\n", argv[0]);
    return 1;
  }
  std::vector<Bytes> corpus(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!read_file(files[i], corpus[i])) {
      std::fprintf(stderr, "fuzz replay: cannot read %s\n", files[i].c_str());
      return 1;
    }
  }
  std::signal(SIGABRT, on_signal);  // a broken property (fuzz_check.hpp)
  std::signal(SIGSEGV, on_signal);
#ifdef FTS_SANITIZER_DEATH_CALLBACK
  __sanitizer_set_death_callback(write_current);  // a sanitizer's report
#endif
  for (const Bytes& input : corpus) run(input);
  std::mt19937_64 rng(seed);
  for (unsigned long long m = 0; m < mutations; ++m) run(mutate(corpus[m % corpus.size()], corpus, rng, max_len));
  std::printf("fuzz replay: %zu seeds and %llu mutations (seed %llu), every property held\n", corpus.size(), mutations,
              seed);
  return 0;
}
