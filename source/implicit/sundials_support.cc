#include "sundials_support.h"

#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace internal
  {
    SundialsContext::SundialsContext()
    {
      if (SUNContext_Create(nullptr, &context) != 0)
        throw std::runtime_error("SUNDIALS: could not create a context.");
    }

    SundialsContext::~SundialsContext()
    {
      SUNContext_Free(&context);
    }

    namespace
    {
      struct PreconditionerSolverContent
      {
        void       *p_data     = nullptr;
        SUNPSetupFn setup      = nullptr;
        SUNPSolveFn solve      = nullptr;
        int         last_flag  = 0;
        int         iterations = 0;
        /** The residual vector (zero: the solves are exact). */
        N_Vector residual = nullptr;
      };

      PreconditionerSolverContent *
      content(SUNLinearSolver S)
      {
        return static_cast<PreconditionerSolverContent *>(S->content);
      }

      SUNLinearSolver_Type
      get_type(SUNLinearSolver)
      {
        return SUNLINEARSOLVER_ITERATIVE;
      }

      int
      set_a_times(SUNLinearSolver, void *, SUNATimesFn)
      {
        return SUNLS_SUCCESS;
      }

      int
      set_preconditioner(SUNLinearSolver S,
                         void           *p_data,
                         SUNPSetupFn     setup,
                         SUNPSolveFn     solve)
      {
        content(S)->p_data = p_data;
        content(S)->setup  = setup;
        content(S)->solve  = solve;
        return SUNLS_SUCCESS;
      }

      int
      initialize(SUNLinearSolver)
      {
        return SUNLS_SUCCESS;
      }

      int
      setup(SUNLinearSolver S, SUNMatrix)
      {
        auto *c = content(S);
        if (c->setup == nullptr)
          return SUNLS_SUCCESS;
        const int flag = c->setup(c->p_data);
        c->last_flag   = flag;
        return flag == 0 ?
                 SUNLS_SUCCESS :
                 (flag > 0 ? SUNLS_PSET_FAIL_REC : SUNLS_PSET_FAIL_UNREC);
      }

      int
      solve(SUNLinearSolver S,
            SUNMatrix,
            N_Vector     x,
            N_Vector     b,
            const double tolerance)
      {
        auto *c = content(S);
        if (c->solve == nullptr)
          return SUNLS_PSOLVE_FAIL_UNREC;
        const int flag = c->solve(c->p_data, b, x, tolerance, SUN_PREC_LEFT);
        c->last_flag   = flag;
        c->iterations  = 1;
        return flag == 0 ?
                 SUNLS_SUCCESS :
                 (flag > 0 ? SUNLS_PSOLVE_FAIL_REC : SUNLS_PSOLVE_FAIL_UNREC);
      }

      int
      num_iterations(SUNLinearSolver S)
      {
        return content(S)->iterations;
      }

      double
      residual_norm(SUNLinearSolver)
      {
        return 0.;
      }

      N_Vector
      residual(SUNLinearSolver S)
      {
        return content(S)->residual;
      }

      sunindextype
      last_flag(SUNLinearSolver S)
      {
        return content(S)->last_flag;
      }

      int
      free_solver(SUNLinearSolver S)
      {
        if (S == nullptr)
          return SUNLS_SUCCESS;
        if (content(S)->residual != nullptr)
          N_VDestroy(content(S)->residual);
        delete content(S);
        S->content = nullptr;
        SUNLinSolFreeEmpty(S);
        return SUNLS_SUCCESS;
      }
    } // namespace

    SUNLinearSolver
    make_preconditioner_solver(SUNContext context)
    {
      SUNLinearSolver S = SUNLinSolNewEmpty(context);
      if (S == nullptr)
        throw std::runtime_error("SUNDIALS: could not create a linear solver.");
      S->content                = new PreconditionerSolverContent();
      S->ops->gettype           = get_type;
      S->ops->setatimes         = set_a_times;
      S->ops->setpreconditioner = set_preconditioner;
      S->ops->initialize        = initialize;
      S->ops->setup             = setup;
      S->ops->solve             = solve;
      S->ops->numiters          = num_iterations;
      S->ops->resnorm           = residual_norm;
      S->ops->resid             = residual;
      S->ops->lastflag          = last_flag;
      S->ops->free              = free_solver;
      return S;
    }



    std::string
    solver_failure_message(const std::string &method,
                           const double       t,
                           const double       h,
                           const std::string &reason,
                           const std::string &sundials_error,
                           const std::string &callback_error)
    {
      std::ostringstream message;
      message << method << " failed at t = " << t << " (step " << h
              << "): " << reason << ". " << sundials_error;
      if (!callback_error.empty())
        message << " [" << callback_error << "]";
      return message.str();
    }



    void
    store_error_message(int         error_code,
                        const char *module,
                        const char *function,
                        char       *message,
                        void       *string)
    {
      auto &text = *static_cast<std::string *>(string);
      text       = std::string(module) + "::" + function + " (" +
             std::to_string(error_code) + "): " + message;
    }

    void
    copy_out(N_Vector x, const unsigned int offset, Vector &out)
    {
      const double *d = data(x) + offset;
      for (unsigned int i = 0; i < out.size(); ++i)
        out[i] = d[i];
    }

    void
    copy_in(const Vector &in, N_Vector x, const unsigned int offset)
    {
      double *d = data(x) + offset;
      for (unsigned int i = 0; i < in.size(); ++i)
        d[i] = in[i];
    }
  } // namespace internal
} // namespace estep
