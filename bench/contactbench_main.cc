// The suite driver: see harness/cli.h.
#include "harness/cli.h"

int main(int argc, char** argv) { return cb::harness::Main(argc, argv); }
