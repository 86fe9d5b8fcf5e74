#ifndef estep_base_mpi_session_h
#define estep_base_mpi_session_h

namespace estep
{
  /**
   * Start MPI, if it is not running, for the parts of estep that need it
   * (Trilinos solvers, HDF5 output); a run that needs none of them does not
   * pay for MPI's start-up. Call finish_mpi() once every object that uses MPI
   * is gone.
   */
  void
  start_mpi();

  /** Finalise MPI if start_mpi() started it. */
  void
  finish_mpi();
} // namespace estep

#endif
