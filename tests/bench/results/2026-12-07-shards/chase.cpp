// Latency of a dependent load: from DRAM (a 256 MB pointer chase on one core), and of a
// line last written by the other core (a 4 MB chase written by cpu 0, chased by cpu 1).
//   g++ -O2 -pthread chase.cpp -o chase && ./chase (not built by CMake)
#include <pthread.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <random>
#include <thread>
#include <vector>
void pin(int c){ cpu_set_t s; CPU_ZERO(&s); CPU_SET(c,&s); pthread_setaffinity_np(pthread_self(),sizeof s,&s); }
struct alignas(64) Node { Node* next; char pad[56]; };
std::vector<Node> make(size_t n, unsigned seed){
  std::vector<Node> v(n); std::vector<size_t> p(n); std::iota(p.begin(),p.end(),0);
  std::shuffle(p.begin()+1,p.end(),std::mt19937(seed));
  for(size_t i=0;i<n;i++) v[p[i]].next=&v[p[(i+1)%n]];
  return v;
}
double chase(Node* s, size_t steps){ auto a=std::chrono::steady_clock::now(); Node* p=s; for(size_t i=0;i<steps;i++) p=p->next; double d=std::chrono::duration<double,std::nano>(std::chrono::steady_clock::now()-a).count(); if(!p) puts(""); return d/steps; }
int main(){
  pin(0);
  auto big=make((256u<<20)/64,1);
  printf("DRAM (256 MB chase, cpu 0): %.0f ns/load\n", chase(&big[0], 2000000));
  auto small=make((4u<<20)/64,2);
  for(int rep=0;rep<3;rep++){
    for(auto& n: small) n.pad[0]++;  // cpu 0 writes every line
    printf("4 MB chase, cpu 0 after its writes: %.0f ns/load; ", chase(&small[0], small.size()));
    for(auto& n: small) n.pad[0]++;
    double d=0; std::thread t([&]{ pin(1); d=chase(&small[0], small.size()); }); t.join();
    printf("cpu 1 after cpu 0's writes: %.0f ns/load\n", d);
  }
}
