// libFuzzer harness (issue 20): any text as a scene file, read and validated by read_scene (the
// YAML, every section, the tunnel's expansion, the rock mass's generation, the overlap checks).
// Its relative paths start in tests/app/bad_scenes, so that the CSV and mesh files there are
// found. Corpus: tests/fuzz/corpus/scene; docs/testing.md.
#include "tests/fuzz/fuzz_reading.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string file = DDAFEM_SOURCE_DIR "/tests/app/bad_scenes/fuzzed.yaml";
  ddafem::fuzz::read_or_refuse(std::string(reinterpret_cast<const char*>(data), size), file, {});
  return 0;
}
