/// @file SlabRunRecord.h
/// @brief One slab run's result (SlabRunResult) as a run record (lsdem/core/ByteWriter.h), bit for bit, so
///        that a run done on another MPI rank writes the same files as one done here.
#pragma once

#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"
#include "studies/SlabRun.h"

namespace lsdem {

void writeSlabRunRecord(ByteWriter<>& out, const SlabRunResult& r);
SlabRunResult readSlabRunRecord(ByteReader& in);

} // namespace lsdem
