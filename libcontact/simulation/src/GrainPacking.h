// Grains, their states and their contact histories as bytes, for GhostDecomposition (private
// to the simulation library). Numbers travel as their bytes, so a receiver's copy is bit for
// bit the sender's.
#pragma once

#include "lsdem/simulation/World.h"

#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"

#include <vector>

namespace lsdem::grainpacking {

/// The buffers ranks exchange, written and read with lsdem's one binary writer and reader; a
/// short read is a DamagedBytes (a bug: both sides run this code).
using Writer = ByteWriter<std::vector<char>>;
using Reader = ByteReader;

/// Everything of a grain (its asset by index into World::assets).
void putGrain(Writer& out, const Grain& g, int assetIndex);
Grain getGrain(Reader& in, const World& world);

/// What a ghost needs each step: pose, velocity and angular momentum.
void putState(Writer& out, const Grain& g);
void getState(Reader& in, Grain& g);

void putHistory(Writer& out, const ShearHistory& h);
void getHistory(Reader& in, ShearHistory& h, std::vector<ShearHistory::Entry>& buffer);

} // namespace lsdem::grainpacking
