// SPDX-License-Identifier: GPL-3.0-or-later
// Every file a morphex library writes (meshes, JSON, plots, indexes' exports) is written to a
// temporary next to its target and renamed into place, so readers never see half a file and a
// failure leaves the old file as it was. A program that stops on a signal removes the temporaries
// of the writes then in progress by calling this from its handler.
#pragma once

namespace morphex {

// Removes the temporary files of writes in progress. Async-signal-safe: a SIGINT handler calls it
// before exiting, so an interrupted run leaves neither a half-written output nor a stray temporary.
void remove_pending_temporary_files() noexcept;

}  // namespace morphex
