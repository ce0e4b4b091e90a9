// brume-vdb-read: Brume's isolated OpenVDB reader (io/vdb_reader.h). brume spawns it for every VDB
// file, so that a file which crashes the OpenVDB library ends this process, not Brume.
#include "io/vdb_reader.h"

int main(int argc, char** argv) { return brume::vdbReaderMain(argc, argv); }
