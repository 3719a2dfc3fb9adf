#include "studies/verify/VerifyReport.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/CsvText.h"
#include "lsdem/core/NumberText.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lsdem::verify {

bool Report::allPass() const
{
    return std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.passes(); });
}

int Report::failures() const
{
    return static_cast<int>(
        std::count_if(checks.begin(), checks.end(), [](const Check& c) { return !c.passes(); }));
}

void writeChecksCsv(const Report& report, const std::string& path)
{
    std::ostringstream csv;
    csv << "case,formulation,quantity,unit,reference,value,error,tolerance,pass,basis\n";
    for (const Check& c : report.checks)
        csv << csvField(c.caseName) << ',' << csvField(c.formulation) << ','
            << csvField(c.quantity) << ',' << csvField(c.unit) << ',' << numberText(c.reference)
            << ',' << numberText(c.value) << ',' << numberText(c.error()) << ','
            << numberText(c.tolerance) << ','
            << (c.informative ? "info" : c.passes() ? "yes" : "no") << ','
            << csvField(c.basis) << '\n';
    writeTextFileAtomically(path, csv.str());
}

void writeSeriesCsv(const Series& series, const std::string& path)
{
    std::ostringstream csv;
    for (size_t k = 0; k < series.columns.size(); ++k)
        csv << (k ? "," : "") << csvField(series.columns[k]);
    csv << '\n';
    for (const std::vector<double>& row : series.rows) {
        for (size_t k = 0; k < row.size(); ++k) csv << (k ? "," : "") << numberText(row[k]);
        csv << '\n';
    }
    writeTextFileAtomically(path, csv.str());
}

} // namespace lsdem::verify
