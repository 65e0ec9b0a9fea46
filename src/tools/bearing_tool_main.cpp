#include <iostream>
int main() { std::cerr << "bearing_tool: being written\n"; return 2; }
