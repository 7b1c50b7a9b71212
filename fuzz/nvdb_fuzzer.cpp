// libFuzzer target: see runNanoVDBInput in fuzz_inputs.h for how the bytes are used.
#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    ps::fuzz::runNanoVDBInput(data, size);
    return 0;
}
