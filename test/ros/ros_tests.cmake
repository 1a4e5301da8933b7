# rostests of the node (issue 3).
