// A slab run's result travelling between MPI ranks as bytes (SlabRunRecord.h, written with
// lsdem's ByteWriter): every field comes back bit for bit.
#include "studies/SlabRunRecord.h"
#include "studies/SlabStudy.h"

#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"

#include <gtest/gtest.h>

using namespace lsdem;

// A real slab run (a 3x3 panel, one step of the study) through a record: every field of the
// result, the P-δ curve, the snapshots' faces and the final displacements, exactly.
TEST(SlabRunRecord, ASlabRunComesBackExactly)
{
    SlabStudyOptions o;
    o.panel.blocksPerSide = 3;
    o.deltaMax = 0.2;
    o.samples = 20;
    const SlabPanel panel(o.panel);
    const auto block = bakeSlabBlock(panel, 0.4, 1.0);
    SlabRunResult r = runSlabCase(o, panel, block, Formulation::Adapted, 1.0, 0.4);
    r.bakeSeconds = 0.25;
    r.error = "none, \"quoted\"";
    ASSERT_FALSE(r.curve.empty());
    ASSERT_FALSE(r.snapshots.empty());

    ByteWriter<> out;
    writeSlabRunRecord(out, r);
    out.text("after");
    ByteReader in(out.bytes());
    const SlabRunResult b = readSlabRunRecord(in);
    EXPECT_EQ(in.text(), "after");  // the run's record ends where it should
    EXPECT_TRUE(in.atEnd());

    EXPECT_EQ(b.formulation, r.formulation);
    EXPECT_EQ(b.sdp, r.sdp);
    EXPECT_EQ(b.vdp, r.vdp);
    EXPECT_EQ(b.nodes, r.nodes);
    EXPECT_EQ(b.meanSpacing, r.meanSpacing);
    EXPECT_EQ(b.stiffness, r.stiffness);
    EXPECT_EQ(b.dt, r.dt);
    EXPECT_EQ(b.stabilityLimit, r.stabilityLimit);
    EXPECT_EQ(b.steps, r.steps);
    EXPECT_EQ(b.bakeSeconds, r.bakeSeconds);
    EXPECT_EQ(b.runSeconds, r.runSeconds);
    EXPECT_EQ(b.nodeChecks, r.nodeChecks);
    EXPECT_EQ(b.stopped, r.stopped);
    EXPECT_EQ(b.error, r.error);
    ASSERT_EQ(b.curve.size(), r.curve.size());
    for (size_t i = 0; i < r.curve.size(); ++i) {
        const SlabSample &x = b.curve[i], &y = r.curve[i];
        EXPECT_EQ(x.delta, y.delta);
        EXPECT_EQ(x.force, y.force);
        EXPECT_EQ(x.centralDrop, y.centralDrop);
        EXPECT_EQ(x.othersMax, y.othersMax);
        EXPECT_EQ(x.frameForce, y.frameForce);
        EXPECT_EQ(x.kinetic, y.kinetic);
    }
    ASSERT_EQ(b.snapshots.size(), r.snapshots.size());
    for (size_t i = 0; i < r.snapshots.size(); ++i) {
        const SlabSnapshot &x = b.snapshots[i], &y = r.snapshots[i];
        EXPECT_EQ(x.delta, y.delta);
        ASSERT_EQ(x.displacement.size(), y.displacement.size());
        for (size_t k = 0; k < y.displacement.size(); ++k) EXPECT_EQ(x.displacement[k], y.displacement[k]);
        ASSERT_EQ(x.faces.size(), y.faces.size());
        for (size_t k = 0; k < y.faces.size(); ++k)
            for (int f = 0; f < 6; ++f) {
                EXPECT_EQ(x.faces[k][f].normal, y.faces[k][f].normal);
                for (int c = 0; c < 4; ++c) EXPECT_EQ(x.faces[k][f].corners[c], y.faces[k][f].corners[c]);
            }
    }
    ASSERT_EQ(b.finalDisplacement.size(), r.finalDisplacement.size());
    for (size_t k = 0; k < r.finalDisplacement.size(); ++k)
        EXPECT_EQ(b.finalDisplacement[k], r.finalDisplacement[k]);
}
