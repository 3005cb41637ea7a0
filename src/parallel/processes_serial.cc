// The processes of a build without MPI: always one (processes.h).
#include "parallel/processes.h"

namespace cb {

int ProcessRank() { return 0; }
int ProcessCount() { return 1; }
bool Distributed() { return false; }
bool AnyProcess(bool mine) { return mine; }
int MinOverProcesses(int mine) { return mine; }
int BroadcastFromZero(int word) { return word; }
std::string MpiVersion() { return ""; }

}  // namespace cb
