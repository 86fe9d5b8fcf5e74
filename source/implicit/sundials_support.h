// Private helpers of the SUNDIALS-based integrators (not installed): a RAII
// SUNContext, a linear solver that applies the user's exact "preconditioner"
// (a direct Newton-matrix solve), error-message capture and vector copies.
#ifndef estep_implicit_sundials_support_h
#define estep_implicit_sundials_support_h

#include <estep/systems/mechanical_system.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_iterative.h>
#include <sundials/sundials_linearsolver.h>

#include <exception>
#include <string>

namespace estep
{
  namespace internal
  {
    /** A SUNContext owned for the lifetime of one integrator. */
    class SundialsContext
    {
    public:
      SundialsContext();
      ~SundialsContext();
      SundialsContext(const SundialsContext &) = delete;
      SundialsContext &
      operator=(const SundialsContext &) = delete;

      operator SUNContext() const
      {
        return context;
      }

    private:
      SUNContext context = nullptr;
    };

    /**
     * A SUNLinearSolver of "iterative" type whose solve is one application of
     * the preconditioner the integrator registers (IDASetPreconditioner,
     * ARKStepSetPreconditioner, KINSetPreconditioner): estep's preconditioner
     * solves the Newton system exactly (ShiftedStiffnessSolver), so this is a
     * direct solve behind SUNDIALS' matrix-free interface. Its setup calls the
     * registered preconditioner setup (the Jacobian setup).
     */
    SUNLinearSolver
    make_preconditioner_solver(SUNContext context);

    /** The message of an ImplicitSolverFailure: @p method failed at time
     * @p t with the step @p h for @p reason, then SUNDIALS' last message and
     * a callback's error, if any. */
    std::string
    solver_failure_message(const std::string &method,
                           const double       t,
                           const double       h,
                           const std::string &reason,
                           const std::string &sundials_error,
                           const std::string &callback_error);

    /** An error handler of IDA, ARKode and KINSOL that stores the last
     * message in the std::string user data. */
    void
    store_error_message(int         error_code,
                        const char *module,
                        const char *function,
                        char       *message,
                        void       *string);

    /**
     * Run the body of a SUNDIALS callback, which returns a SUNDIALS status:
     * an exception must not cross the C code, so it becomes @p
     * failure_status and its message is kept in @p message (the integrator
     * reports it when the step fails).
     */
    template <typename Body>
    int
    guarded_callback(std::string &message,
                     const int    failure_status,
                     Body       &&body)
    {
      try
        {
          return body();
        }
      catch (const std::exception &e)
        {
          message = e.what();
          return failure_status;
        }
    }

    /** Pointer to the data of a serial N_Vector. */
    inline double *
    data(N_Vector x)
    {
      return N_VGetArrayPointer_Serial(x);
    }

    /** Copy n entries of @p x from @p offset into @p out. */
    void
    copy_out(N_Vector x, const unsigned int offset, Vector &out);

    /** Copy @p in into @p x from @p offset. */
    void
    copy_in(const Vector &in, N_Vector x, const unsigned int offset);
  } // namespace internal
} // namespace estep

#endif
