// The estep command. Everything it does lives in the library: see
// estep::run_application().
#include <estep/app/application.h>

int
main(int argc, char **argv)
{
  return estep::run_application(argc, argv);
}
