// hgridlab's header-only core in one include, without the full library's
// dependencies (HDF5 and the rest):
//   #include <hgridlab/core.hpp>     (target hgridlab::core; C++20, OpenMP if present)
// The grid, its tilted form and decomposition, the contact list, the contact
// history and the sums over pairs. <hgridlab/hgridlab.hpp> has everything.
#pragma once

#include "hgridlab/grid/version.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/grid/brute_force.hpp"
#include "hgridlab/grid/counters.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/grid/params.hpp"
#include "hgridlab/grid/tilted.hpp"
#include "hgridlab/grid/tilted_box.hpp"
#include "hgridlab/domain/decomposition.hpp"
#include "hgridlab/domain/decomposed_query.hpp"
#include "hgridlab/contacts/contact_history.hpp"
#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/contacts/pair_sum.hpp"
