#define BOOST_TEST_MODULE deepcheck_geometry
#define BOOST_TEST_DYN_LINK
#include <boost/test/unit_test.hpp>
