// report.hpp - writes the experiments' results: results.md (each table next to the
// paper's figures) and machine-readable table1.tsv, orientation.tsv, combined.tsv,
// limits.tsv.
#ifndef HLEXP_REPORT_HPP
#define HLEXP_REPORT_HPP

#include <string>
#include <vector>

#include "experiment.hpp"
#include "limits.hpp"

namespace hlexp {

struct Results {
    std::vector<Table1Row> table1;
    std::vector<OrientationRow> orientation;
    std::vector<CombinedRow> combined;
    std::vector<LimitsRow> limits;
    int reps = 0;
};

// Writes the files that have rows. Returns false with a one-line reason on failure.
bool write_results(const std::string &dir, const Results &r, std::string *err);

}  // namespace hlexp
#endif
