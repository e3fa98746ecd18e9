// Implemented by the foundation's statistical tests.
#include "support/chi2.h"
