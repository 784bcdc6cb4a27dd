// Where the real data sets (pcl_room_scans, hdl32_scan_pair, ...) are found: one resolver for the
// tests, benchmarks and tools, so they all look in the same places in the same order.
#pragma once

#include <string>
#include <vector>

namespace tacs {

/// The per-user data cache that scripts/get_test_data.sh fills:
/// $XDG_CACHE_HOME/tacs_graphs/data, else ~/.cache/tacs_graphs/data.
std::string userDataCacheDir();

/// The folders searched for data sets, in order. When $TACS_SHARED_DATA_DIR is set it is the only
/// one (an explicit choice is never replaced by another copy); else the nearest shared/data beside
/// `source_dir` or a folder above it (a clone with shared/ beside it), then userDataCacheDir().
std::vector<std::string> dataSearchDirs(const std::string& source_dir);

/// The folder of data set `set`, "<dir>/<set>/" for the first search folder that has it; empty
/// when none has.
std::string findDataSet(const std::string& set, const std::string& source_dir);

/// What to tell a user when `set` is missing: the set, the command that gets it and where it was
/// looked for.
std::string missingDataSetMessage(const std::string& set, const std::string& source_dir);

}  // namespace tacs
