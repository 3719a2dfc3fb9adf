// The whole simulation seen from one rank (Simulation.h): its contacts, world and numbers
// gathered across the ranks it is split over, in one process's order, for the measures that
// need every grain at once (micromechanics, D²min).
#include "lsdem/simulation/Simulation.h"

#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"
#include "lsdem/simulation/GhostDecomposition.h"

#include <algorithm>
#include <tuple>

namespace lsdem {

namespace {

/// One process's list order: grain pairs by (first, second), then grain–boundary contacts by
/// (grain, boundary), then grain–membrane contacts by (membrane, grain).
auto listKey(const ContactRecord& r)
{
    return r.membrane >= 0  ? std::make_tuple(2, r.membrane, r.first)
           : r.boundary < 0 ? std::make_tuple(0, r.first, r.second)
                            : std::make_tuple(1, r.first, r.boundary);
}

} // namespace

std::vector<ContactRecord> Simulation::wholeContactRecords() const
{
    if (!mGhosts) return contactRecords();
    // Each contact from the rank that owns its first grain (the others hold the same numbers).
    const std::vector<int>& ids = mGhosts->globalIds();
    std::vector<char> mine;
    ByteWriter<std::vector<char>> out(mine);
    for (ContactRecord r : contactRecords()) {
        if (!integratesGrain(size_t(r.first))) continue;
        r.first = ids[size_t(r.first)];
        if (r.second >= 0) r.second = ids[size_t(r.second)];
        out.value(r.first).value(r.second).value(r.boundary).value(r.membrane).value(r.nodes);
        out.values(r.force.data(), 3).values(r.centre.data(), 3).values(r.normal.data(), 3);
        out.values(r.shift.data(), 3).values(r.spread.data(), 9);
    }
    std::vector<char> all;
    std::vector<size_t> starts;
    mGhosts->ranks().allGather(mine, all, starts);
    std::vector<ContactRecord> records;
    ByteReader in(all);
    while (!in.atEnd()) {
        ContactRecord r;
        r.first = in.value<int>();
        r.second = in.value<int>();
        r.boundary = in.value<int>();
        r.membrane = in.value<int>();
        r.nodes = in.value<int>();
        in.values(r.force.data(), 3);
        in.values(r.centre.data(), 3);
        in.values(r.normal.data(), 3);
        in.values(r.shift.data(), 3);
        in.values(r.spread.data(), 9);
        records.push_back(r);
    }
    std::sort(records.begin(), records.end(),
              [](const ContactRecord& a, const ContactRecord& b) { return listKey(a) < listKey(b); });
    return records;
}

World Simulation::wholeWorld() const
{
    return mGhosts ? mGhosts->gatherWorld(mWorld) : mWorld;
}

std::vector<double> Simulation::numbersFromRankZero(const std::vector<double>& numbers) const
{
    if (!mGhosts) return numbers;
    std::vector<char> mine;
    if (mGhosts->rank() == 0) ByteWriter<std::vector<char>>(mine).numbers(numbers);
    std::vector<char> all;
    std::vector<size_t> starts;
    mGhosts->ranks().allGather(mine, all, starts);
    ByteReader in(all.data() + starts[0], all.data() + starts[1]);
    return in.numbers();
}

} // namespace lsdem
