// SPDX-License-Identifier: GPL-3.0-or-later
// libretrieval's result structs as JSON (nlohmann's convention, as morphex/json.h for libbool):
// what `morphex index|ls|query|evaluate --json`, the Python module and the web server print.
#pragma once

#include <nlohmann/json.hpp>

#include "morphex/index.h"
#include "morphex/index_db.h"
#include "morphex/retrieval.h"

namespace morphex {

// nearest_neighbor, first_tier, second_tier, e_measure, dcg, queries.
void to_json(nlohmann::json& j, const RetrievalScores& scores);
// A class's scores (the keys above) and models, its size. The class's name is the caller's key.
void to_json(nlohmann::json& j, const ClassScores& scores);
// recall, precision (the interpolated precision at each recall level).
void to_json(nlohmann::json& j, const PrecisionRecall& curve);
// name, path, distance, id (the mesh's row in the index).
void to_json(nlohmann::json& j, const Neighbour& neighbour);
// indexed, skipped, skipped_failed, failed, errors [{path, error}], seconds, meshes_per_minute
// (described or failed meshes per minute, 0 when none), processes.
void to_json(nlohmann::json& j, const IndexSummary& summary);
// An index entry: name, path, status, error (when it failed), faces, volume (exact, as read),
// hash, seconds, indexed_at, settings, settings_id (the first 8 digits of text_hash(settings)),
// repair (the recorded repair report, null when none) and descriptors {kind: vector} (empty when
// the entry was loaded without them).
void to_json(nlohmann::json& j, const IndexedMesh& entry);

}  // namespace morphex
