// The image fuzzer compiles stb_image itself so that libFuzzer gets coverage of its decoders
// and ASan/UBSan check them: Debian's libstb.so is neither instrumented nor checked. These
// definitions in the executable take precedence over the shared library's.
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
