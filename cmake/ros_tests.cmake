# rostests (issue 3 onwards).
