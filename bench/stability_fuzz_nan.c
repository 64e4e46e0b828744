/* No NaN, no infinite loop: 200000 random extreme pairs (magnitudes 10^-100
 * to 10^100, aspect ratios to 10^7, some with r12 = 0) through the five
 * methods of pw85_contact_function_method; counts statuses and non-finite
 * outputs (docs/stability.md).
 * Built by bench/meson.build:  build/bench/stability_fuzz_nan 1  (argument: seed) */
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include "pw85.h"
static double urand(void){ return rand()/(RAND_MAX+1.0); }
static void rot(double R[9]){ double w=urand()-.5,x=urand()-.5,y=urand()-.5,z=urand()-.5,n=sqrt(w*w+x*x+y*y+z*z); w/=n;x/=n;y/=n;z/=n;
 double m[9]={1-2*(y*y+z*z),2*(x*y-w*z),2*(x*z+w*y),2*(x*y+w*z),1-2*(x*x+z*z),2*(y*z-w*x),2*(x*z-w*y),2*(y*z+w*x),1-2*(x*x+y*y)}; for(int i=0;i<9;i++)R[i]=m[i];}
static void mkq(double a,double b,double c,double q[6]){ double R[9]; rot(R); double s[3]={a*a,b*b,c*c}; int k=0;
 for(int i=0;i<3;i++)for(int j=i;j<3;j++){ double t=0; for(int l=0;l<3;l++) t+=s[l]*R[3*i+l]*R[3*j+l]; q[k++]=t; } }
static long permeth[5][8];
int main(int argc,char**argv){ srand(argc>1?atoi(argv[1]):1); long bad=0, tot=0, st[8]={0}, maxit=0;
 for(int it=0; it<200000; it++){
   double scale=pow(10, (urand()-0.5)*200); double asp=pow(10, urand()*7);
   double q1[6],q2[6],r[3];
   mkq(scale, scale/asp*(urand()+0.5), scale*urand()/ (urand()<0.5?asp:1)+scale*1e-7, q1);
   mkq(scale*(urand()+0.1), scale/asp, scale*(urand()+0.01), q2);
   double d=scale*pow(10,(urand()-0.5)*8); for(int i=0;i<3;i++) r[i]=d*(urand()-0.5);
   if (it%97==0) { r[0]=r[1]=r[2]=0; }
   for(int m=0;m<5;m++){ pw85_result res; int s=pw85_contact_function_method(r,q1,q2,m,&res); tot++;
     if (s==PW85_ERR_NOT_SPD || s==PW85_ERR_INVALID_ARGUMENT) { st[7]++; continue; }
     st[-s<7?-s:6]++; if(s!=0) permeth[m][-s<7?-s:6]++; if(res.iterations>maxit) maxit=res.iterations;
     if(!isfinite(res.mu2)||!isfinite(res.lambda)||!isfinite(res.mu2_error)||res.mu2<0) { bad++; if(bad<10) printf("bad m=%d s=%d mu2=%g lam=%g err=%g scale=%g asp=%g\n",m,s,res.mu2,res.lambda,res.mu2_error,scale,asp);} }
 }
  for(int m=0;m<5;m++) printf("method %d: noconv %ld inaccurate %ld\n",m,permeth[m][3],permeth[m][6]);
 printf("total %ld bad %ld OK %ld noconv %ld inaccurate %ld rejected %ld maxit %ld\n",tot,bad,st[0],st[3],st[6],st[7],maxit); return 0; }
