#include "studies/SlabScene.h"

#include "studies/SlabModel.h"

#include "lsdem/scene/SceneWriter.h"

#include <sstream>

namespace lsdem {

Scene makeSlabScene(const SlabStudyOptions& o, Formulation formulation,
                    std::shared_ptr<const GrainAsset> block, double dt)
{
    const SlabPanel panel(o.panel);
    Scene scene;
    scene.path = "slab_scene.toml";
    AssetSpec asset;
    asset.name = "block";
    asset.loaded = block;
    asset.where = "slab block";
    scene.assets.push_back(asset);
    scene.materials.push_back({"glass", o.material.density});
    scene.materials.push_back({"rigid", 0.0});
    ContactSpec contact;
    contact.model = slabContactModel(o, formulation);
    contact.model.damping = ViscousDamping(o.material.restitution);
    contact.materialA = contact.materialB = 0;
    contact.where = "blocks";
    scene.contacts.push_back(contact);
    contact.materialB = 1;
    contact.where = "blocks against the frame and the indenter";
    scene.contacts.push_back(contact);
    for (const SlabBlock& b : panel.blocks()) {
        GrainSpec g;
        g.name = b.name;
        g.asset = 0;
        g.material = 0;
        g.pose = slabBlockPose(b, block->inputFrame);
        g.where = b.name;
        scene.grains.push_back(g);
    }
    for (const SlabBlock& b : panel.frame()) {
        BoundarySpec f;
        f.name = b.name;
        f.shape = BoundaryShape::LevelSet;
        f.material = 1;
        f.asset = 0;
        f.pose = slabBlockPose(b, block->inputFrame);
        f.where = b.name;
        scene.boundaries.push_back(f);
    }
    BoundarySpec indenter;
    indenter.name = "indenter";
    indenter.shape = BoundaryShape::Sphere;
    indenter.material = 1;
    const Vec3 top = panel.blocks()[panel.centralBlock()].center +
                     Vec3(0, 0, 0.5 * o.panel.thickness);
    indenter.center = top + Vec3(0, 0, o.indenterRadius);  // touching the central block's top
    indenter.radius = o.indenterRadius;
    indenter.velocity = Vec3(0, 0, -o.speed);
    indenter.where = "indenter";
    scene.boundaries.push_back(indenter);
    scene.gravity = Vec3(0, 0, -o.material.gravity);
    scene.globalDamping = o.material.globalDamping;
    scene.timeStep.fixed = dt;
    scene.end.boundary = static_cast<int>(scene.boundaries.size()) - 1;
    scene.end.displacement = slabDeltaMax(o);
    const double duration = slabDeltaMax(o) / o.speed;
    scene.output.historyPeriod = duration / o.samples;
    scene.output.vtkPeriod = duration / 20.0;
    return scene;
}

void writeSlabScene(const Scene& scene, const SlabStudyOptions& o, const std::string& path)
{
    const SlabStiffness k = slabStiffness(o);
    std::ostringstream header;
    header << "The interlocked slab of Feldfogel et al. (2024), Fig. 5 and 6, written by\n"
           << "`lsdem-study slab`: " << o.panel.blocksPerSide << "x" << o.panel.blocksPerSide
           << " blocks, L = " << o.panel.blockSize << " mm, t = " << o.panel.thickness
           << " mm, interlocking angle " << o.panel.angleDeg << " deg (docs/slab.md).\n"
           << "The frame is a ring of fixed level-set blocks of the same shape; a sphere pushes\n"
           << "the central block down. Run with\n"
           << "  build/tools/lsdem-run slab_scene.toml --out slab-run\n"
           << "slab-run/boundary_indenter.csv then holds P (fz) against the indenter's "
              "displacement.\n"
           << "Units: mm, tonne, s, N. kn* = E/L = " << k.knStar << " N/mm^3 (E = "
           << o.material.youngModulus << " MPa).\n"
           << "The time step is safety x the stability limit of a block between two neighbours.";
    writeSceneFile(scene, path, header.str());
}

} // namespace lsdem
