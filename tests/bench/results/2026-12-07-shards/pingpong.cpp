// One cache line bounced between cpu 0 and cpu 1 (a round trip: each waits for the other's
// store), and 8 MB written on cpu 0 then read in order on cpu 1. Not built by CMake:
//   g++ -O2 -pthread pingpong.cpp -o pingpong && ./pingpong
#include <atomic>
#include <thread>
#include <chrono>
#include <cstdio>
#include <pthread.h>
#include <vector>
#include <cstdint>
alignas(64) std::atomic<int> flag{0};
void pin(int c){ cpu_set_t s; CPU_ZERO(&s); CPU_SET(c,&s); pthread_setaffinity_np(pthread_self(),sizeof s,&s); }
int main(){
  const int N=200000;
  std::thread t([&]{ pin(1); for(int i=0;i<N;i++){ while(flag.load(std::memory_order_acquire)!=2*i+1); flag.store(2*i+2,std::memory_order_release);} });
  pin(0);
  auto t0=std::chrono::steady_clock::now();
  for(int i=0;i<N;i++){ flag.store(2*i+1,std::memory_order_release); while(flag.load(std::memory_order_acquire)!=2*i+2); }
  auto t1=std::chrono::steady_clock::now();
  t.join();
  printf("round trip %.0f ns\n", std::chrono::duration<double,std::nano>(t1-t0).count()/N);
  // bandwidth-ish: caller writes 8 MB buffer, other thread reads it
  std::vector<uint64_t> buf(1<<20);
  for(int rep=0;rep<3;rep++){
    for(auto&x:buf) x+=rep;
    uint64_t s=0; double dt;
    std::thread r([&]{ pin(1); auto a=std::chrono::steady_clock::now(); for(size_t i=0;i<buf.size();i+=8) s+=buf[i]; dt=std::chrono::duration<double,std::nano>(std::chrono::steady_clock::now()-a).count(); });
    r.join();
    auto a=std::chrono::steady_clock::now(); uint64_t s2=0; for(size_t i=0;i<buf.size();i+=8) s2+=buf[i]; double d2=std::chrono::duration<double,std::nano>(std::chrono::steady_clock::now()-a).count();
    printf("lines written by cpu0, read by cpu1: %.1f ns/line; re-read by cpu0: %.1f ns/line (%lu)\n", dt/(buf.size()/8), d2/(buf.size()/8), (unsigned long)(s+s2));
  }
}
