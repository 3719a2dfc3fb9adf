#include "studies/SlabModel.h"

#include "lsdem/ls/Bake.h"
#include "lsdem/simulation/StableStep.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lsdem {

SlabStiffness slabStiffness(const SlabStudyOptions& o)
{
    SlabStiffness k;
    // A traction p on a face shortens a block of length L by p·L/E: kn* = E/L.
    k.knStar = o.knStar > 0.0 ? o.knStar : o.material.youngModulus / o.panel.blockSize;
    k.ksStar = o.ksStar > 0.0 ? o.ksStar : k.knStar / (2.0 * (1.0 + o.material.poisson));
    const double sRef = o.referenceSdp > 0.0
                            ? o.referenceSdp
                            : *std::max_element(o.sdps.begin(), o.sdps.end());
    // A node's area on an equilateral mesh of edge s is (√3/2)·s².
    k.kn = o.knOriginal > 0.0 ? o.knOriginal : k.knStar * 0.5 * std::sqrt(3.0) * sRef * sRef;
    k.ks = k.kn * (k.ksStar / k.knStar);
    return k;
}

ContactModel slabContactModel(const SlabStudyOptions& o, Formulation formulation)
{
    const SlabStiffness k = slabStiffness(o);
    ContactModel m;
    m.formulation = formulation;
    m.testing = o.testing;
    m.normalStiffness = normalModel(formulation).stiffnessPerArea() ? k.knStar : k.kn;
    // single-node and volume carry no shear springs (contact.md).
    const bool shear = normalModel(formulation).perNodeForces();
    m.shearStiffness = shear ? (normalModel(formulation).stiffnessPerArea() ? k.ksStar : k.ks) : 0.0;
    m.friction = shear ? o.material.friction : 0.0;
    return m;
}

std::shared_ptr<const GrainAsset> bakeSlabBlock(const SlabPanel& panel, double vdp, double sdp)
{
    BakeOptions bake;
    bake.voxelSize = vdp;
    bake.nodePlacement = NodePlacement::Spacing;
    bake.nodeSpacing = sdp;
    bake.areaRule = AreaRule::Mesh;
    std::ostringstream text;
    const SlabPanelOptions& p = panel.options();
    text << "slab block L=" << p.blockSize << " t=" << p.thickness << " angle=" << p.angleDeg
         << " voxel " << vdp << " node_spacing " << sdp;
    bake.optionsText = text.str();
    std::vector<std::string> warnings;  // only "spacing finer than voxels", expected in a study
    return std::make_shared<const GrainAsset>(
        bakeMesh(panel.referenceMesh(), "slab block", bake, warnings));
}

double slabTimeStep(const SlabStudyOptions& o, const SlabPanel& panel, const GrainAsset& block,
                    Formulation formulation)
{
    const SlabStiffness k = slabStiffness(o);
    const double mass = o.material.density * block.mass.volume;
    // One shared face in full contact: kn*·A (adapted: the nodes' areas add up to A; symmetric
    // testing adds both sides at half weight), or kn per node on it (original).
    const double meanNodeArea = block.nodes.totalArea() / double(std::max<size_t>(1, block.nodes.size()));
    const ContactModel model = slabContactModel(o, formulation);
    const double face =
        model.normal().patchStiffness(model.normalStiffness, panel.sharedFaceArea(), meanNodeArea);
    // A block squeezed between its two x neighbours; shear springs stiffer than the normal
    // ones would set the scale instead. Not the block's fastest mode (its turn about z is about
    // 1.5 times as fast, docs/slab.md), which timeStepSafety leaves room for.
    const double stiffest = 2.0 * face * std::max(1.0, k.ksStar / k.knStar);
    // Under global damping the springs act stiffer for the step (StableStep.h).
    return o.timeStepSafety * 2.0 *
           std::sqrt(mass / (globalDampingStiffening(o.material.globalDamping) * stiffest));
}

} // namespace lsdem
