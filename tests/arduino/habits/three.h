#ifndef THREE_H_
#define THREE_H_
int addThree(int x);
#endif
