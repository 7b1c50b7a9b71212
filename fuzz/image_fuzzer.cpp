// libFuzzer target: see runImageInput in fuzz_inputs.h for how the bytes are used.
#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    ps::setWarningsQuiet(true);
    ps::fuzz::runImageInput(data, size);
    return 0;
}
