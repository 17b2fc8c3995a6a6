#!/bin/sh
# Stands in for an MPI rank that dies mid-render (killed, out of memory, lost node).
sleep 1
kill -9 $$
