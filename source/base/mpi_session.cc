#include <deal.II/base/mpi.h>

#include <estep/base/mpi_session.h>

namespace estep
{
  namespace
  {
    bool started_here = false;
  }



  void
  start_mpi()
  {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (initialized)
      return;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
    started_here = true;
  }



  void
  finish_mpi()
  {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (started_here && !finalized)
      MPI_Finalize();
    started_here = false;
  }
} // namespace estep
