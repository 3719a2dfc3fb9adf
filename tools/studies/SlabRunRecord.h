/// @file SlabRunRecord.h
/// @brief One slab run's result (SlabRunResult) as a run record (RecordBytes.h), bit for bit, so
///        that a run done on another MPI rank writes the same files as one done here.
#pragma once

#include "studies/RecordBytes.h"
#include "studies/SlabRun.h"

namespace lsdem {

void writeSlabRunRecord(RecordWriter& out, const SlabRunResult& r);
SlabRunResult readSlabRunRecord(RecordReader& in);

} // namespace lsdem
