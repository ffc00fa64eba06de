#pragma once
// Publishing a folder written under a staging name: the target is, at every instant, either its previous
// complete content (or absent when it had none) or the new complete content, even when the process is killed.
#include <string>

namespace vilslam {

// Moves the folder `staging` to `target`, replacing a previous `target` folder. An existing target is swapped
// with the staging folder in one atomic step (renameat2 RENAME_EXCHANGE) and the previous content, now under
// `staging`, is removed afterwards; a file system without the exchange gets the previous target renamed aside
// first (a kill in between leaves no target, never a partial one). Throws std::runtime_error naming both paths.
void publish_directory(const std::string& staging, const std::string& target);

}  // namespace vilslam
