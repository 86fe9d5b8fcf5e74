// Part of libestep in ESTEP_SANITIZE builds only (CMakeLists.txt): dlclose()
// does nothing, so that a shared object once loaded stays loaded. Open MPI
// loads its components with dlopen() and unloads those it does not select (in
// MPI_Init, MPI_File_open, ...) and all of them in MPI_Finalize. What they
// allocated would then be reported by LeakSanitizer at exit from stack frames
// in modules that are gone ("<unknown module>"), which no suppression can name,
// and what the components still held in their own variables would count as
// leaked. With the components kept, that memory stays reachable, and the rest
// is reported from named modules, which tests/sanitizers/lsan.supp names. estep
// itself never unloads a library.
//
// Process-wide: this definition comes before the C library's in the search
// order of every program linked with libestep (the sanitizers' dlclose
// interceptor forwards to it).
extern "C" int
dlclose(void *) noexcept
{
  return 0;
}
