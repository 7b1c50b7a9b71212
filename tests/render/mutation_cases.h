// One of Veach's mutations beside the bidirectional one (tests of transport/mlt/veach/):
// with only those two enabled, the image agrees with BDPT's (agreement.h), the mutation
// under test was proposed, and every mutation that applied was accepted, but not always.
#pragma once
#include <gtest/gtest.h>

#include <cstdio>
#include <ostream>
#include <string>

#include "agreement.h"
#include "render_helpers.h"

namespace ps::test {

struct MutationCase {
    const char* name;
    std::string weights;  // --mlt-mutations
    std::string (*scene)();
    int bdptSpp, mltSpp;
    const char* applies;  // the mutation that must have been proposed and accepted
    double detectableBias = 0.02;
};

inline void PrintTo(const MutationCase& c, std::ostream* os) { *os << c.name; }

inline void expectMutationAgreesAndApplies(const MutationCase& c) {
    const std::string integrator = "mlt:" + c.weights;
    expectAgreement(AgreementCase{c.name, c.scene(), {"bdpt", integrator}, c.bdptSpp, 16, {{integrator, c.mltSpp}},
                                  c.detectableBias});
    const RenderResult r = renderString(c.scene(), c.mltSpp, 1, 0, integrator);
    bool found = false;
    for (const MetropolisStats::Kind& k : r.metropolis.kinds) {
        const double rate = MetropolisStats::rate(k.accepted, k.proposed);
        std::printf("  %s: %s: %lld proposed, acceptance %.3f\n", c.name, k.name.c_str(), k.proposed, rate);
        if (k.name == c.applies) found = k.proposed > 0;
        if (k.proposed > 0) {
            EXPECT_GT(rate, 0.0) << k.name;
            EXPECT_LT(rate, 1.0) << k.name;
        }
    }
    EXPECT_TRUE(found) << c.applies;
}

}  // namespace ps::test
