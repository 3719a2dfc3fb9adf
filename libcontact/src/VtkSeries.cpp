#include "lsdem/contact/VtkSeries.h"
