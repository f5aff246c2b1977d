#include <lodestone/graphslam/NodeStore.h>

#include <stdexcept>
#include <string>

namespace lodestone::graphslam {

void NodeStore::add(TNodeID id, NodeRecord record) {
    if (id != records_.size()) {
        throw std::logic_error("node " + std::to_string(id) + " registered out of order (expected " +
                               std::to_string(records_.size()) + ")");
    }
    records_.push_back(std::move(record));
}

void NodeStore::releaseDepth(TNodeID id) {
    if (has(id)) records_[id].depth.reset();
}

const NodeRecord& NodeStore::at(TNodeID id) const {
    if (!has(id)) throw std::out_of_range("no node " + std::to_string(id));
    return records_[id];
}

}  // namespace lodestone::graphslam
