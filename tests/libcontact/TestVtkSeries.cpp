#include "lsdem/contact/VtkSeries.h"
#include <gtest/gtest.h>
