#include "lsdem/contact/SceneFile.h"
#include <gtest/gtest.h>
