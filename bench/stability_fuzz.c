/* Random extreme pairs through every method of pw85_contact_function_method
 * (docs/stability.md): magnitudes 10^-100 to 10^100, aspect ratios to 10^6;
 * reference: maximisation of f in __float128. Counts "silent" failures
 * (status PW85_OK with an error above the documented accuracy).
 * Built by bench/meson.build:  build/bench/stability_fuzz 3  (argument: seed) */
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include "pw85.h"
typedef __float128 real;
static double urand(void){ return rand()/(RAND_MAX+1.0); }
static void rot(double R[9]){ double w=urand()-.5,x=urand()-.5,y=urand()-.5,z=urand()-.5,n=sqrt(w*w+x*x+y*y+z*z); w/=n;x/=n;y/=n;z/=n;
 double m[9]={1-2*(y*y+z*z),2*(x*y-w*z),2*(x*z+w*y),2*(x*y+w*z),1-2*(x*x+z*z),2*(y*z-w*x),2*(x*z-w*y),2*(y*z+w*x),1-2*(x*x+y*y)}; for(int i=0;i<9;i++)R[i]=m[i];}
static void mkq(double a,double b,double c,double q[6]){ double R[9]; rot(R); double s[3]={a*a,b*b,c*c}; int k=0;
 for(int i=0;i<3;i++)for(int j=i;j<3;j++){ double t=0; for(int l=0;l<3;l++) t+=s[l]*R[3*i+l]*R[3*j+l]; q[k++]=t; } }
static int ev(real lam,const double r[3],const double q1[6],const double q2[6],real*f,real*df,real*d2f){
  real q[6],d[6]; for(int i=0;i<6;i++){q[i]=(1-lam)*(real)q1[i]+lam*(real)q2[i]; d[i]=(real)q2[i]-(real)q1[i];}
  real d0=q[0]; if(!(d0>0))return 0; real l10=q[1]/d0,l20=q[2]/d0,d1=q[3]-l10*q[1]; if(!(d1>0))return 0;
  real e=q[4]-l20*q[1],l21=e/d1,d2=q[5]-l20*q[2]-l21*e; if(!(d2>0))return 0;
  real b[3]={r[0],r[1],r[2]},s[3],u[3],v[3];
  for(int pass=0;pass<2;pass++){ real*x=pass?v:s; real y0=b[0],y1=b[1]-l10*y0,y2=b[2]-l20*y0-l21*y1; x[2]=y2/d2; x[1]=y1/d1-l21*x[2]; x[0]=y0/d0-l10*x[1]-l20*x[2];
    if(!pass){u[0]=d[0]*s[0]+d[1]*s[1]+d[2]*s[2];u[1]=d[1]*s[0]+d[3]*s[1]+d[4]*s[2];u[2]=d[2]*s[0]+d[4]*s[1]+d[5]*s[2];b[0]=u[0];b[1]=u[1];b[2]=u[2];}}
  real phi=(real)r[0]*s[0]+(real)r[1]*s[1]+(real)r[2]*s[2], p1=-(s[0]*u[0]+s[1]*u[1]+s[2]*u[2]), p2=2*(u[0]*v[0]+u[1]*v[1]+u[2]*v[2]);
  real p=lam*(1-lam); *f=p*phi; *df=(1-2*lam)*phi+p*p1; *d2f=-2*phi+2*(1-2*lam)*p1+p*p2; return 1; }
static double ref(const double r[3],const double q1[6],const double q2[6]){ real lo=0,hi=1,f,df,d2f;
  for(int k=0;k<45;k++){ real m=(lo+hi)/2; if(!ev(m,r,q1,q2,&f,&df,&d2f)) return NAN; if(df>0)lo=m; else hi=m;}
  real lam=(lo+hi)/2; for(int k=0;k<6;k++){ if(!ev(lam,r,q1,q2,&f,&df,&d2f)) return NAN; real n=lam-df/d2f; if(!(n>lo&&n<hi))break; lam=n;}
  ev(lam,r,q1,q2,&f,&df,&d2f); return (double)f; }
int main(int argc,char**argv){ srand(argc>1?atoi(argv[1]):1); double acc[5]={1e-14,1e-10,1e-12,1e-12,1e-9}; long silent[5]={0},n=0; double mx[5]={0};
 for(int it=0; it<20000; it++){
   double scale=pow(10, (urand()-0.5)*200); double asp=pow(10, urand()*6);
   double q1[6],q2[6],r[3];
   mkq(scale, scale/asp*(urand()+0.5), scale*urand()/ (urand()<0.5?asp:1)+scale*1e-6, q1);
   mkq(scale*(urand()+0.1), scale/asp, scale*(urand()+0.01), q2);
   double d=scale*pow(10,(urand()-0.5)*8); for(int i=0;i<3;i++) r[i]=d*(urand()-0.5);
   double rf=ref(r,q1,q2); if(!(rf>0)) continue; n++;
   for(int m=0;m<5;m++){ pw85_result res; int s=pw85_contact_function_method(r,q1,q2,m,&res); if(s==PW85_ERR_NOT_SPD) continue;
     double e=fabs(res.mu2-rf)/rf; if(s==0 && e>acc[m]) { silent[m]++; if(silent[m]<4) printf("silent m=%d e=%g scale=%g asp=%g\n",m,e,scale,asp);} if(s==0&&e>mx[m]) mx[m]=e; }
 }
 printf("pairs %ld\n",n); for(int m=0;m<5;m++) printf("method %d: silent %ld, max err of OK results %.2e\n",m,silent[m],mx[m]); return 0; }
