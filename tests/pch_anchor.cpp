// Anchors the precompiled header shared by the test binaries.
int main() {
  return 0;
}
