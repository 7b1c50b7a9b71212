// Embeds the generated coefficient tables (about 9.4 MB each) as read-only data with the
// assembler's .incbin, so that no compiler parses them as literals. The included header
// carries their checksums: it changes whenever the data do, which makes compiler caches
// (ccache hashes sources, not .incbin'd files) rebuild this object.
#include "rgb2spec_tables.h"

#include <cstdint>

#ifndef PS_RGB2SPEC_DIR
#error "PS_RGB2SPEC_DIR must name the directory of the generated tables"
#endif

#define PS_EMBED_TABLE(index, file)                      \
    ".pushsection .rodata\n"                             \
    ".balign 64\n"                                       \
    ".globl ps_rgb2spec_table_" #index "\n"              \
    ".type ps_rgb2spec_table_" #index ", @object\n"      \
    "ps_rgb2spec_table_" #index ":\n"                    \
    ".incbin \"" PS_RGB2SPEC_DIR "/" file "\"\n"         \
    ".size ps_rgb2spec_table_" #index ", . - ps_rgb2spec_table_" #index "\n" \
    ".popsection\n"

__asm__(PS_EMBED_TABLE(0, "rgb2spec_srgb.bin") PS_EMBED_TABLE(1, "rgb2spec_rec2020.bin")
            PS_EMBED_TABLE(2, "rgb2spec_dci-p3.bin") PS_EMBED_TABLE(3, "rgb2spec_aces2065-1.bin"));

namespace ps {

uint64_t rgbTableExpectedChecksum(int space) {
    static const uint64_t kChecksums[4] = {PS_RGB2SPEC_CHECKSUM_0, PS_RGB2SPEC_CHECKSUM_1, PS_RGB2SPEC_CHECKSUM_2,
                                           PS_RGB2SPEC_CHECKSUM_3};
    return kChecksums[space];
}

}  // namespace ps
