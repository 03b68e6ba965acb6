// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for the pipeline JSON parser and validator: any text is either a valid
// pipeline or a PipelineError listing located problems. Nothing runs.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "morphex/pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace morphex::pipeline;
  morphex::fuzz::limit_inputs();
  const std::string text(reinterpret_cast<const char*>(data), size);
  morphex::fuzz::expect_only<PipelineError>([&] {
    const nlohmann::json document = parse_document(text, "fuzz.json");
    const Pipeline pipeline = validate(document, "fuzz.json", {{"size", "1/2"}}, {"input", "stem"});
    if (pipeline.order.size() != pipeline.stages.size())
      morphex::fuzz::finding("a validated pipeline has no complete stage order");
  });
  return 0;
}
