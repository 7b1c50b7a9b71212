// The toolbox's techniques by name, each run on a TestIntegrand with a budget of about n
// integrand evaluations, so that they can be compared per evaluation and per second
// (`pathspace mc`). Each entry composes a point set (point_sets.h) with an estimator.
#pragma once
#include <string>
#include <vector>

#include "mc/mc_estimate.h"
#include "mc/rng.h"
#include "mc/test_integrands.h"

namespace ps {

struct Technique {
    std::string name, description;
    bool (*applies)(const TestIntegrand&);
    McEstimate (*run)(const TestIntegrand&, int n, Rng&);  // seconds include point generation
};

const std::vector<Technique>& techniques();
const Technique* findTechnique(const std::string& name);  // nullptr if unknown

}  // namespace ps
