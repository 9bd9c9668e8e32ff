// Replays a fuzz target's corpus without libFuzzer: every file named on the command line
// (a directory: every regular file in it, in name order) is read and handed to the
// target's LLVMFuzzerTestOneInput once. A broken property aborts (fuzz_check.hpp), and
// the sanitized build reports memory errors and UB, as under libFuzzer; the seeds and the
// findings kept as seeds are regression tests of the default test run (gcc, no clang),
// while the mutation runs are .ci/fuzz.sh's (tests/fuzz/README.md).
// Exit codes: 0 replayed at least one input; 1 nothing to replay or a file unreadable.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

bool replay(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "fuzz replay: cannot read %s\n", file.c_str());
    return false;
  }
  const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  // A copy of its own size, so that a read past the input is a heap overflow (ASan).
  std::vector<std::uint8_t> data(bytes.begin(), bytes.end());
  LLVMFuzzerTestOneInput(data.empty() ? nullptr : data.data(), data.size());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path arg = argv[i];
    if (std::filesystem::is_directory(arg)) {
      std::vector<std::filesystem::path> in_dir;
      for (const auto& entry : std::filesystem::directory_iterator(arg))
        if (entry.is_regular_file()) in_dir.push_back(entry.path());
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "fuzz replay: no inputs (usage: %s FILE|DIR...)\n", argv[0]);
    return 1;
  }
  for (const auto& f : files)
    if (!replay(f)) return 1;
  std::printf("fuzz replay: %zu inputs, every property held\n", files.size());
  return 0;
}
