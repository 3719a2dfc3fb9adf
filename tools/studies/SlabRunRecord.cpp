#include "studies/SlabRunRecord.h"

namespace lsdem {

namespace {

void append(std::vector<double>& v, const Vec3& p)
{
    v.insert(v.end(), {p.x(), p.y(), p.z()});
}

Vec3 vectorAt(const std::vector<double>& v, size_t& i)
{
    const Vec3 p(v.at(i), v.at(i + 1), v.at(i + 2));
    i += 3;
    return p;
}

} // namespace

void writeSlabRunRecord(ByteWriter<>& out, const SlabRunResult& r)
{
    out.integer(static_cast<long long>(r.formulation)).number(r.sdp).number(r.vdp).integer(r.nodes);
    out.number(r.meanSpacing).number(r.stiffness).number(r.dt).number(r.stabilityLimit);
    out.integer(r.steps).number(r.bakeSeconds).number(r.runSeconds).integer(r.nodeChecks);
    std::vector<double> curve;
    for (const SlabSample& s : r.curve)
        curve.insert(curve.end(),
                     {s.delta, s.force, s.centralDrop, s.othersMax, s.frameForce, s.kinetic});
    out.numbers(curve);
    out.integer(static_cast<long long>(r.snapshots.size()));
    for (const SlabSnapshot& s : r.snapshots) {
        std::vector<double> moved, faces;
        for (const Vec3& d : s.displacement) append(moved, d);
        for (const std::array<SlabFace, 6>& block : s.faces)
            for (const SlabFace& f : block) {
                for (const Vec3& c : f.corners) append(faces, c);
                append(faces, f.normal);
            }
        out.number(s.delta).numbers(moved).numbers(faces);
    }
    std::vector<double> ends;
    for (const Vec3& d : r.finalDisplacement) append(ends, d);
    out.numbers(ends).integer(r.stopped ? 1 : 0).text(r.error);
}

SlabRunResult readSlabRunRecord(ByteReader& in)
{
    SlabRunResult r;
    r.formulation = Formulation(in.integer());
    r.sdp = in.number();
    r.vdp = in.number();
    r.nodes = int(in.integer());
    r.meanSpacing = in.number();
    r.stiffness = in.number();
    r.dt = in.number();
    r.stabilityLimit = in.number();
    r.steps = in.integer();
    r.bakeSeconds = in.number();
    r.runSeconds = in.number();
    r.nodeChecks = in.integer();
    const std::vector<double> curve = in.numbers();
    for (size_t i = 0; i + 6 <= curve.size(); i += 6)
        r.curve.push_back({curve[i], curve[i + 1], curve[i + 2], curve[i + 3], curve[i + 4],
                           curve[i + 5]});
    for (long long n = in.integer(); n > 0; --n) {
        SlabSnapshot s;
        s.delta = in.number();
        const std::vector<double> moved = in.numbers(), faces = in.numbers();
        for (size_t i = 0; i < moved.size();) s.displacement.push_back(vectorAt(moved, i));
        for (size_t i = 0; i < faces.size();) {
            std::array<SlabFace, 6> block;
            for (SlabFace& f : block) {
                for (Vec3& c : f.corners) c = vectorAt(faces, i);
                f.normal = vectorAt(faces, i);
            }
            s.faces.push_back(block);
        }
        r.snapshots.push_back(std::move(s));
    }
    const std::vector<double> ends = in.numbers();
    for (size_t i = 0; i < ends.size();) r.finalDisplacement.push_back(vectorAt(ends, i));
    r.stopped = in.integer() != 0;
    r.error = in.text();
    return r;
}

} // namespace lsdem
