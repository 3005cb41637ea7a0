// The suite driver: see harness/cli.h.
#include "harness/cli.h"
#include "harness/interrupt.h"

int main(int argc, char** argv) {
  // Before anything else, so that a signal at any time stops the run the same way.
  cb::harness::InstallInterruptHandlers();
  return cb::harness::Main(argc, argv);
}
