// Door: a workspace file (`--workspace ws.yaml`, core::parse_workspace_yaml): boxes,
// cylinders, meshes, allowed contacts. A mesh it names is looked up, not read here.

#include "fuzz_input.hpp"
#include "telear/core/workspace.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)telear::core::parse_workspace_yaml(telear::fuzz::text(data, size),
                                           "/nonexistent/fuzz_workspace.yaml");
  return 0;
}
