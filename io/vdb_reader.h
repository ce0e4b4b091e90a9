// The isolated OpenVDB reader: OpenVDB 10 segfaults on some corrupt files (a byte flipped in
// plasmadxr_fluid_data_0001.vdb at offset 9415 is one), and a forked child deadlocks in TBB, so Brume
// reads every file in a separate executable, brume-vdb-read, installed beside brume:
//
//   brume-vdb-read load FILE GRID MEMORY_LIMIT_BYTES OUT   -> OUT/grid.nvdb + OUT/result.json
//   brume-vdb-read info FILE MEMORY_LIMIT_BYTES OUT        -> OUT/result.json
//
// OUT is a folder (for debugging by hand) or "-": then the grid goes to file descriptor 4 and
// result.json to 5, the anonymous memory files (memfd_create) that Brume passes, so that no temp
// folder exists for a Ctrl-C or a kill to leave behind. result.json is {"ok": true, ...} or {"ok":
// false, "error": "one sentence"}; it is written last (by rename, in a folder), and Brume reads it only
// after a clean exit, so a reader that dies leaves none. The reader writes its progress ("42\n", percent of the
// file's bytes read) on file descriptor 3 when that is open. The parent side (loadVdbDensity,
// inspectVdb) spawns it without a shell and turns a death by signal or a non-zero exit into one
// sentence: "FILE: the OpenVDB reader crashed reading this file (it is corrupt or not a VDB file)."
#pragma once

namespace brume {

// main() of brume-vdb-read; returns 0 whenever result.json was written (errors included).
int vdbReaderMain(int argc, char** argv);

}  // namespace brume
