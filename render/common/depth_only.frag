// Depth-only passes write no colour.
void main() {}
