// SPDX-License-Identifier: GPL-3.0-or-later
// libretrieval's result structs as JSON (morphex/retrieval_json.h has the keys).
#include "morphex/retrieval_json.h"

namespace morphex {

void to_json(nlohmann::json& j, const RetrievalScores& s) {
  j = {{"nearest_neighbor", s.nearest_neighbor},
       {"first_tier", s.first_tier},
       {"second_tier", s.second_tier},
       {"e_measure", s.e_measure},
       {"dcg", s.dcg},
       {"queries", s.queries}};
}

void to_json(nlohmann::json& j, const ClassScores& c) {
  to_json(j, c.scores);
  j["models"] = c.models;
}

void to_json(nlohmann::json& j, const PrecisionRecall& pr) {
  j = {{"recall", pr.recall}, {"precision", pr.precision}};
}

void to_json(nlohmann::json& j, const Neighbour& n) {
  j = {{"name", n.name}, {"path", n.path}, {"distance", n.distance}, {"id", n.id}};
}

void to_json(nlohmann::json& j, const IndexSummary& s) {
  const std::size_t failed = s.errors.size();
  const double per_minute = s.seconds > 0 ? 60.0 * double(s.indexed + failed) / s.seconds : 0;
  j = {{"indexed", s.indexed},
       {"skipped", s.skipped},
       {"skipped_failed", s.skipped_failed},
       {"failed", failed},
       {"errors", nlohmann::json::array()},
       {"seconds", s.seconds},
       {"meshes_per_minute", per_minute},
       {"processes", s.processes}};
  for (const auto& [path, error] : s.errors)
    j["errors"].push_back({{"path", path}, {"error", error}});
}

void to_json(nlohmann::json& j, const IndexedMesh& m) {
  nlohmann::json repair;  // null: not repaired
  if (!m.repair.empty()) try {
      repair = nlohmann::json::parse(m.repair);
    } catch (const nlohmann::json::exception&) {
      repair = m.repair;  // a damaged record, shown as text
    }
  j = {{"name", m.name},         {"path", m.path},
       {"status", m.status},     {"faces", m.faces},
       {"volume", m.volume},     {"hash", m.hash},
       {"seconds", m.seconds},   {"indexed_at", m.indexed_at},
       {"settings", m.settings}, {"settings_id", text_hash(m.settings).substr(0, 8)},
       {"repair", repair},       {"descriptors", m.descriptors}};
  if (!m.error.empty()) j["error"] = m.error;
}

}  // namespace morphex
